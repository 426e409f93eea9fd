#include "frame_stages/residual_errors.hpp"

#include <algorithm>

#include <glm/geometric.hpp>

namespace latsim::pipelines::frame_stages {

namespace {
constexpr double kDegPerRad = 57.295779513082320876798;
}  // namespace

ResidualErrors::ResidualErrors(const Compositor& compositor, results::LatencyRecorder& recorder,
                               const tracker::MotionSource& motion, double ipd_m, bool stereo)
    : compositor_(compositor), recorder_(recorder), motion_(motion), ipd_m_(ipd_m), stereo_(stereo) {}

void ResidualErrors::on_scanout(const display::ScanoutSpan& span) {
  const int rewarps = compositor_.rewarps_of(span.image_id);
  if (rewarps < 0) return;
  const results::ImageRecord* img = recorder_.images().find(span.image_id);
  if (img == nullptr) return;
  if (!orientation_) {
    orientation_ = &recorder_.distribution_ref("residual_orientation_error_deg");
    position_ = &recorder_.distribution_ref("residual_position_error_mm");
  }
  Bucket& b = buckets_[static_cast<size_t>(std::min(rewarps, kBuckets - 1))];
  // One value per sample of the span, each against the truth at its photon time.
  des::TickStepper t(span.photons);
  for (uint64_t i = 0; i < span.photons.count; ++i, t.step()) {
    const tracker::Pose truth = tracker::eye_pose(motion_.pose_at(t.time()), span.eye, ipd_m_, stereo_);
    const double deg = tracker::angle_between(img->eye_pose.orientation, truth.orientation) * kDegPerRad;
    const double mm = glm::length(img->eye_pose.position_m - truth.position_m) * 1e3;
    orientation_->add(deg);
    position_->add(mm);
    b.orientation_deg.add(deg);
    b.position_mm.add(mm);
  }
}

}  // namespace latsim::pipelines::frame_stages
