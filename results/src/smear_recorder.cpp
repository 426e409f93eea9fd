#include "latsim/results/smear_recorder.hpp"
#include "latsim/units/units.hpp"


namespace latsim::results {

namespace {
}  // namespace

double head_angular_speed_rad_s(const tracker::MotionSource& motion, des::Time t) {
  const des::Time h = des::Time::us(500);
  const des::Time a = t < h ? des::Time::zero() : t - h;
  const des::Time b = a + h + h;
  return tracker::angle_between(motion.pose_at(a).orientation, motion.pose_at(b).orientation) / (b - a).to_seconds();
}

SmearRecorder::SmearRecorder(LatencyRecorder& recorder, const tracker::MotionSource& motion)
    : smear_(recorder.distribution_ref("smear_arcmin")), motion_(motion), still_(motion.is_still()) {}

void SmearRecorder::on_scanout(const display::ScanoutSpan& span) {
  // One value per sample of the span, each at its own photon time.
  stats::TickStepper t(span.photons);
  for (uint64_t i = 0; i < span.photons.count; ++i, t.step()) {
    const double speed = still_ ? 0.0 : head_angular_speed_rad_s(motion_, t.time());
    smear_.add(speed * span.lit_duration.to_seconds() * units::kArcminPerRad);
  }
}

}  // namespace latsim::results
