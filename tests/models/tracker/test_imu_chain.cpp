// The tracking chain as a headset runs it: gyro readings, their noise, the
// complementary filter's response to a step in angular velocity (delay and
// jitter derived by hand below), and a delayed reference with and without
// aligning it to the instant it was measured.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "latsim/tracker/complementary_filter.hpp"
#include "latsim/tracker/imu.hpp"
#include "latsim/tracker/imu_chain.hpp"
#include "latsim/tracker/optical_reference.hpp"
#include "latsim/tracker/tracker.hpp"
#include "latsim/tracker/transport.hpp"
#include "latsim/units/units.hpp"

using namespace latsim::tracker;
using latsim::des::PeriodicSchedule;
using latsim::des::RandomStream;
using latsim::des::RationalSeconds;
using latsim::des::Time;
using latsim::units::kRadPerDeg;

namespace {

/// At rest until `start`, then turning about y at `rate_deg_s`: a step in angular velocity.
class StepTurn final : public MotionSource {
 public:
  StepTurn(Time start, double rate_deg_s) : start_(start), rate_deg_s_(rate_deg_s) {}
  Pose pose_at(Time t) const override {
    const double turned = t > start_ ? rate_deg_s_ * (t - start_).to_seconds() : 0.0;
    return Pose{{0.0, 1.6, 0.0}, quat_from_yaw_pitch(turned * kRadPerDeg, 0.0)};
  }
  std::string name() const override { return "step"; }

 private:
  Time start_;
  double rate_deg_s_;
};

double yaw_deg(const glm::dquat& q) { return yaw_of(q) / kRadPerDeg; }

}  // namespace

TEST_CASE("noise-free gyro readings integrate to the true orientation at every reading", "[imu]") {
  // Each reading is the body-frame rotation over its interval divided by
  // the interval, so the product of the increments is the truth itself.
  const ConstantAngularVelocity motion(Pose{{0, 0, 0}, quat_from_yaw_pitch(0.3, 0.1)}, {0.2, 1.0, -0.4}, 250.0);
  Imu imu(ImuParams{}, PeriodicSchedule(Time::zero(), RationalSeconds{1, 1000}), motion, RandomStream(1, "imu"));
  glm::dquat q = motion.pose_at(Time::zero()).orientation;
  for (int64_t k = 1; k <= 500; ++k) {
    const ImuReading r = imu.read(k);
    q = glm::normalize(q * quat_from_rotation_vector(r.rate_rad_s * 1e-3));
  }
  CHECK(angle_between(q, motion.pose_at(Time::ms(500)).orientation) < 1e-9);
}

TEST_CASE("gyro white noise has the density's per-reading deviation", "[imu]") {
  // A reading at rate f averages white noise of density N over 1/f: its
  // standard deviation is N sqrt(f); 20000 readings give it within 2 %.
  ImuParams p;
  p.gyro_noise_density_deg_s_rthz = 0.01;
  const StillMotion still(Pose{});
  Imu imu(p, PeriodicSchedule(Time::zero(), RationalSeconds{1, 800}), still, RandomStream(3, "imu"));
  double sum2 = 0.0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) sum2 += std::pow(imu.read(k).rate_rad_s.x / kRadPerDeg, 2);
  CHECK(std::sqrt(sum2 / n) == Approx(0.01 * std::sqrt(800.0)).epsilon(0.02));
}

TEST_CASE("timestamps are whole ticks of the device clock and readings saturate at the range", "[imu]") {
  ImuParams p;
  p.timestamp_tick = Time::us(40);
  p.range_deg_s = 100.0;
  const ConstantAngularVelocity fast(Pose{}, {0, 1, 0}, 300.0);
  Imu imu(p, PeriodicSchedule(Time::us(7), RationalSeconds{1, 1000}), fast, RandomStream(1, "imu"));
  const ImuReading r = imu.read(3);
  CHECK(r.measured_at == Time::us(3007));
  CHECK(r.stamp == Time::us(3000));
  CHECK(r.rate_rad_s.y == Approx(100.0 * kRadPerDeg));
}

TEST_CASE("the chain's delay and jitter for a step in angular velocity", "[imu][fusion]") {
  // Derivation. Readings come every D = 1 ms and each is the mean rate over
  // the interval ending at it. A step to w at t0 falls u = t_k - t0 before
  // the reading that straddles it, u uniform on (0, D] over step phases, and
  // that reading is w u / D. The runtime's angular velocity (the newest
  // reading) first reaches w/2 at t_k when u >= D/2, else one reading later:
  // the chain's delay at the sensor is u or u + D, uniform on [D/2, 3D/2):
  // mean D, standard deviation D / sqrt(12). A USB link polled every P =
  // 1 ms with a fixed delay of 0.5 ms adds a wait uniform on [0, P) for
  // reports whose phase against the poll is uniform: mean P/2 + 0.5 ms and a
  // further variance P^2 / 12. Both together: mean 2 ms, standard deviation
  // sqrt(2/12) ms = 0.408 ms. The orientation, integrated from the readings,
  // is the truth at every reading: its error at the report's visibility is
  // the turn since the reading, never more.
  const double w = 200.0;
  std::vector<double> delays_ms;
  double worst_orientation_error_deg = 0.0;
  for (int i = 0; i < 400; ++i) {
    // Step phases spread over the reading and poll intervals (golden-ratio offsets).
    const double frac_step = std::fmod(i * 0.6180339887498949, 1.0);
    const double frac_poll = std::fmod(i * 0.7548776662466927, 1.0);
    const Time t0 = Time::ms(20) + Time::from_ms(frac_step);
    const StepTurn motion(t0, w);
    TrackerParams tp;
    tp.period = RationalSeconds{1, 1000};
    tp.imu = ImuChainParams{};
    Tracker tracker(tp, motion, RandomStream(1, "tracker"));
    UsbHidParams up;
    up.poll_clock.phase = Time::from_ms(frac_poll);
    up.os_delay = Time::us(500);
    UsbHidLink link(up, RandomStream(1, "usb"));
    RuntimeFusion fusion(*tp.imu, motion, RandomStream(1, "ref"));
    std::optional<double> delay;
    for (int64_t k = 0; k < 60; ++k) {
      const TrackerSample s = tracker.sample(k);
      const Carriage c = link.carry(s.ready_at);
      const TrackerSample f = fusion.fuse(s, c.visible);
      const double err = std::abs(yaw_deg(f.pose.orientation) - yaw_deg(motion.pose_at(s.measured_at).orientation));
      worst_orientation_error_deg = std::max(worst_orientation_error_deg, err);
      if (!delay && f.angular_velocity_rad_s->y >= 0.5 * w * kRadPerDeg) delay = (c.visible - t0).to_ms();
    }
    REQUIRE(delay);
    delays_ms.push_back(*delay);
  }
  double mean = 0.0, var = 0.0;
  for (double d : delays_ms) mean += d;
  mean /= static_cast<double>(delays_ms.size());
  for (double d : delays_ms) var += (d - mean) * (d - mean);
  const double sd = std::sqrt(var / static_cast<double>(delays_ms.size() - 1));
  // 400 quasi-random phases: the mean within 0.03 ms, the deviation within 5 %.
  CHECK(mean == Approx(2.0).margin(0.03));
  CHECK(sd == Approx(std::sqrt(2.0 / 12.0)).epsilon(0.05));
  CHECK(worst_orientation_error_deg < 1e-9);
}

TEST_CASE("a delayed reference drags an unaligned complementary filter back by its age", "[fusion]") {
  // A gyro whose bias is unknown to the filter (1 deg/s) while the head
  // turns at w = 100 deg/s; fixes every P = 10 ms, each applied d = 5 ms
  // after it was measured. Aligned to the instant the fix measured, the
  // fix's error is the drift alone, which the integral term removes. Not
  // aligned, each fix also compares with an estimate d later, a turn of
  // w d = 0.5 deg: the lag L obeys L' = (1 - g) L + g (w d - b d') with g =
  // 1 - exp(-P / tau), so it settles near w d, a delay of d.
  const double w = 100.0;
  const Time d = Time::ms(5);
  for (bool aligned : {true, false}) {
    const ConstantAngularVelocity motion(Pose{}, {0, 1, 0}, w);
    FusionParams fp;
    fp.orientation_time_constant = Time::ms(50);
    fp.bias_time_constant = Time::s(2);
    fp.align_reference = aligned;
    ComplementaryFilter filter(fp);
    ImuParams ip;
    Imu imu(ip, PeriodicSchedule(Time::zero(), RationalSeconds{1, 1000}), motion, RandomStream(1, "imu"));
    ReferenceParams rp;
    rp.period = RationalSeconds{1, 100};
    rp.latency = d;
    OpticalReference ref(rp, motion, RandomStream(1, "ref"));
    filter.start(motion.pose_at(Time::zero()), Time::zero());
    int64_t next_fix = 0;
    double lag_deg = 0.0;
    for (int64_t k = 1; k <= 3000; ++k) {
      ImuReading r = imu.read(k);
      r.rate_rad_s.y += 1.0 * kRadPerDeg;  // the bias the filter must learn
      filter.integrate(r);
      while (ref.fix(next_fix).available_at <= r.measured_at) CHECK(filter.correct(ref.fix(next_fix++)));
      lag_deg = yaw_deg(motion.pose_at(r.measured_at).orientation) - yaw_deg(filter.orientation());
    }
    if (aligned) {
      CHECK(std::abs(lag_deg) < 0.02);
      CHECK(filter.bias_rad_s().y / kRadPerDeg == Approx(1.0).margin(0.05));
    } else {
      // The settled lag is w d plus what the bias leaves: within 0.1 deg of 0.5.
      CHECK(lag_deg == Approx(w * d.to_seconds()).margin(0.1));
    }
  }
}
