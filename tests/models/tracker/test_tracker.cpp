// Tracker timing (exact periods, jitter, order) and measurement noise.
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/geometric.hpp>

#include "latsim/tracker/tracker.hpp"

using namespace latsim::tracker;
using latsim::des::RandomStream;
using latsim::des::RationalSeconds;
using latsim::des::Time;

namespace {

TrackerParams ntsc_params() {
  TrackerParams p;
  p.period = RationalSeconds::period_of_hz(60000, 1001);
  return p;
}

}  // namespace

TEST_CASE("tracker sample times are exact at 59.94 Hz after hours", "[tracker]") {
  const StillMotion still(Pose{});
  Tracker tracker(ntsc_params(), still, RandomStream(1, "tracker"));
  CHECK(tracker.sample(0).measured_at == Time::zero());
  // Sample one million is 1e6 * 1001/60000 s = 16683.333... s, floored to the picosecond.
  const TrackerSample s = tracker.sample(1'000'000);
  CHECK(s.measured_at == Time::ps(16'683'333'333'333'333));
  CHECK(tracker.nominal_time(1'000'000) == s.measured_at);
  CHECK(tracker.nominal_time(3) == Time::ps(50'050'000'000));
}

TEST_CASE("phase and internal delay shift measurement and readiness", "[tracker]") {
  TrackerParams p = ntsc_params();
  p.clock.phase = Time::ms(3);
  p.internal_delay = Time::us(7500);
  const ConstantAngularVelocity spin(Pose{}, {0, 1, 0}, 90.0);
  Tracker tracker(p, spin, RandomStream(1, "tracker"));
  const TrackerSample s = tracker.sample(2);
  CHECK(s.index == 2);
  CHECK(s.measured_at == Time::ms(3) + Time::ps(33'366'666'666));
  CHECK(s.ready_at == s.measured_at + Time::us(7500));
  // Without noise the pose is exactly the motion's at the measurement time.
  const Pose truth = spin.pose_at(s.measured_at);
  CHECK(s.pose.orientation == truth.orientation);
  CHECK(s.pose.position_m == truth.position_m);
}

TEST_CASE("samples must be drawn in increasing index order", "[tracker]") {
  const StillMotion still(Pose{});
  Tracker tracker(ntsc_params(), still, RandomStream(1, "tracker"));
  (void)tracker.sample(4);
  CHECK_THROWS_AS(tracker.sample(4), std::logic_error);
  CHECK_THROWS_AS(tracker.sample(2), std::logic_error);
  CHECK(tracker.sample(9).index == 9);
}

TEST_CASE("uniform jitter stays within bounds and keeps times increasing", "[tracker]") {
  TrackerParams p = ntsc_params();
  p.jitter = Time::ms(2);
  p.clock.phase = Time::ms(5);
  const StillMotion still(Pose{});
  Tracker tracker(p, still, RandomStream(7, "tracker"));
  double sum_ms = 0.0;
  Time lo = Time::zero();
  Time hi = Time::zero();
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const TrackerSample s = tracker.sample(k);
    const Time offset = s.measured_at - tracker.nominal_time(k);
    lo = std::min(lo, offset);
    hi = std::max(hi, offset);
    sum_ms += offset.to_ms();
  }
  CHECK(lo >= -Time::ms(2));
  CHECK(hi <= Time::ms(2));
  CHECK(lo < -Time::us(1990));  // the whole range is used
  CHECK(hi > Time::us(1990));
  // Mean 0, standard error 2/sqrt(3)/sqrt(n) ms = 0.008 ms.
  CHECK(std::abs(sum_ms / n) < 0.04);
}

TEST_CASE("normal jitter has the configured spread", "[tracker]") {
  TrackerParams p = ntsc_params();
  p.jitter = Time::ms(1);  // small against the period: clamping practically never acts
  p.jitter_shape = TrackerParams::Normal;
  p.clock.phase = Time::ms(10);
  const StillMotion still(Pose{});
  Tracker tracker(p, still, RandomStream(7, "tracker"));
  double sum = 0.0;
  double sum_sq = 0.0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const double off = (tracker.sample(k).measured_at - tracker.nominal_time(k)).to_ms();
    sum += off;
    sum_sq += off * off;
  }
  CHECK(std::abs(sum / n) < 0.03);  // standard error 0.007 ms
  CHECK(std::sqrt(sum_sq / n) == Approx(1.0).epsilon(0.03));
}

TEST_CASE("jitter larger than the period never reorders samples", "[tracker]") {
  TrackerParams p = ntsc_params();
  p.jitter = Time::ms(12);
  p.jitter_shape = TrackerParams::Normal;
  const StillMotion still(Pose{});
  Tracker tracker(p, still, RandomStream(7, "tracker"));
  Time previous = -Time::ms(1);
  int clamped = 0;
  for (int k = 0; k < 20000; ++k) {
    const TrackerSample s = tracker.sample(k);
    REQUIRE(s.measured_at > previous);
    REQUIRE(s.measured_at >= Time::zero());
    if (s.measured_at == previous + Time::ps(1)) ++clamped;
    previous = s.measured_at;
  }
  CHECK(clamped > 0);  // the clamp was exercised
}

TEST_CASE("trackers are deterministic per seed and noise does not disturb jitter", "[tracker]") {
  TrackerParams p = ntsc_params();
  p.jitter = Time::ms(1);
  TrackerParams noisy = p;
  noisy.noise_enabled = true;
  noisy.noise_covariance = NoiseCovariance::Identity() * 1e-4;
  const StillMotion still(Pose{});
  Tracker a(p, still, RandomStream(3, "tracker"));
  Tracker b(p, still, RandomStream(3, "tracker"));
  Tracker c(noisy, still, RandomStream(3, "tracker"));
  Tracker d(p, still, RandomStream(4, "tracker"));
  bool any_difference = false;
  for (int k = 0; k < 100; ++k) {
    const Time ta = a.sample(k).measured_at;
    CHECK(b.sample(k).measured_at == ta);
    CHECK(c.sample(k).measured_at == ta);
    any_difference = any_difference || d.sample(k).measured_at != ta;
  }
  CHECK(any_difference);
}

TEST_CASE("noise sample covariance matches the configured covariance", "[tracker]") {
  // A correlated, positive definite covariance: C = B B^T.
  NoiseCovariance b = NoiseCovariance::Zero();
  b.diagonal() << 2e-3, 1e-3, 3e-3, 4e-3, 2e-3, 1e-3;
  b(1, 0) = 1e-3;
  b(2, 1) = -1.5e-3;
  b(4, 3) = 2e-3;
  b(5, 0) = 1e-3;
  b(3, 2) = 0.5e-3;
  const NoiseCovariance cov = b * b.transpose();

  TrackerParams p = ntsc_params();
  p.noise_enabled = true;
  p.noise_covariance = cov;
  const Pose truth{{0.5, 1.6, -0.2}, quat_from_yaw_pitch(0.8, 0.3)};
  const StillMotion still(truth);
  Tracker tracker(p, still, RandomStream(11, "tracker"));

  const int n = 100000;
  Eigen::Matrix<double, 6, 1> sum = Eigen::Matrix<double, 6, 1>::Zero();
  NoiseCovariance sum_outer = NoiseCovariance::Zero();
  for (int k = 0; k < n; ++k) {
    const TrackerSample s = tracker.sample(k);
    const glm::dvec3 dp = s.pose.position_m - truth.position_m;
    const glm::dvec3 dr = rotation_vector_between(truth.orientation, s.pose.orientation);
    Eigen::Matrix<double, 6, 1> e;
    e << dp.x, dp.y, dp.z, dr.x, dr.y, dr.z;
    sum += e;
    sum_outer += e * e.transpose();
  }
  const Eigen::Matrix<double, 6, 1> mean = sum / n;
  const NoiseCovariance sample_cov = (sum_outer - n * mean * mean.transpose()) / (n - 1);
  for (int i = 0; i < 6; ++i) {
    const double sd_i = std::sqrt(cov(i, i));
    CHECK(std::abs(mean(i)) < 0.02 * sd_i);
    for (int j = 0; j < 6; ++j) {
      INFO("entry " << i << "," << j);
      // Standard error of a covariance entry is about sd_i sd_j sqrt(2 / n) = 0.0045 sd_i sd_j.
      CHECK(std::abs(sample_cov(i, j) - cov(i, j)) < 0.025 * sd_i * std::sqrt(cov(j, j)));
    }
  }
}

TEST_CASE("noise factors cover semidefinite matrices and reject invalid ones", "[tracker]") {
  NoiseCovariance position_only = NoiseCovariance::Zero();
  position_only.diagonal() << 1e-4, 4e-4, 9e-4, 0.0, 0.0, 0.0;
  position_only(0, 1) = position_only(1, 0) = 2e-4;  // x and y fully correlated
  const NoiseCovariance f = noise_factor(position_only);
  CHECK((f * f.transpose() - position_only).cwiseAbs().maxCoeff() < 1e-18);

  NoiseCovariance indefinite = NoiseCovariance::Identity();
  indefinite(0, 1) = indefinite(1, 0) = 2.0;
  CHECK_THROWS_WITH(noise_factor(indefinite), Catch::Contains("not positive semidefinite"));
  NoiseCovariance asymmetric = NoiseCovariance::Identity();
  asymmetric(0, 1) = 0.5;
  CHECK_THROWS_WITH(noise_factor(asymmetric), Catch::Contains("not symmetric"));

  TrackerParams p = ntsc_params();
  p.noise_enabled = true;
  p.noise_covariance = indefinite;
  const StillMotion still(Pose{});
  CHECK_THROWS_AS(Tracker(p, still, RandomStream(1, "tracker")), std::invalid_argument);
}

TEST_CASE("position-only noise leaves the orientation exact", "[tracker]") {
  TrackerParams p = ntsc_params();
  p.noise_enabled = true;
  p.noise_covariance = NoiseCovariance::Zero();
  p.noise_covariance.diagonal() << 1e-4, 1e-4, 1e-4, 0.0, 0.0, 0.0;
  const Pose truth{{0.0, 1.7, 0.0}, quat_from_yaw_pitch(0.4, 0.0)};
  const StillMotion still(truth);
  Tracker tracker(p, still, RandomStream(5, "tracker"));
  const TrackerSample s = tracker.sample(0);
  CHECK(angle_between(s.pose.orientation, truth.orientation) < 1e-15);
  CHECK(glm::length(s.pose.position_m - truth.position_m) > 0.0);
}
