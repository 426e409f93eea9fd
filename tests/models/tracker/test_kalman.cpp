// The Kalman predictor: covariance against an independent scalar Riccati
// recursion, smoothing of a noisy still head over an hour, unbiased tracking
// of a constant rate, and the hard cases (sign flips, half turns, 1 us
// spacing, jitter).
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>
#include <glm/geometric.hpp>

#include "latsim/des/random.hpp"
#include "latsim/tracker/kalman_predictor.hpp"
#include "latsim/tracker/tracker.hpp"
#include "kalman_steady_state.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using namespace latsim::tracker;
using latsim::des::RandomStream;
using latsim::des::RationalSeconds;
using latsim::des::Time;
using latsim::testing::ScalarSteadyState;
using latsim::testing::scalar_steady_state;

namespace {


KalmanParams params_with_noise(double orientation_stddev_deg, double position_stddev_m, double psd_deg = 100.0) {
  KalmanParams p;
  p.angular_accel_noise_deg_s2_rthz = psd_deg;
  p.measurement_covariance = NoiseCovariance::Zero();
  for (int i = 0; i < 3; ++i) {
    p.measurement_covariance(i, i) = position_stddev_m * position_stddev_m;
    p.measurement_covariance(i + 3, i + 3) = std::pow(orientation_stddev_deg * units::kRadPerDeg, 2);
  }
  return p;
}

TrackerParams tracker_params(int64_t hz, double orientation_stddev_deg, double position_stddev_m) {
  TrackerParams p;
  p.period = RationalSeconds::period_of_hz(hz);
  p.noise_enabled = orientation_stddev_deg > 0 || position_stddev_m > 0;
  p.noise_covariance = params_with_noise(orientation_stddev_deg, position_stddev_m).measurement_covariance;
  return p;
}

double min_eigenvalue(const KalmanPredictor::Matrix6& m) {
  return Eigen::SelfAdjointEigenSolver<KalmanPredictor::Matrix6>(m).eigenvalues().minCoeff();
}

}  // namespace

TEST_CASE("Kalman covariance reaches the steady state of the scalar Riccati recursion", "[kalman]") {
  const double sigma_deg = 0.1, psd_deg = 100.0;
  KalmanPredictor kf(params_with_noise(sigma_deg, 0.001, psd_deg));
  const StillMotion still(Pose{});
  // Noise-free samples keep the estimated rate exactly zero, so the error
  // transition is exactly [[I, dt I], [0, I]] and P follows the recursion.
  Tracker tracker(tracker_params(60, 0.0, 0.0), still, RandomStream(3, "tracker"));
  for (int64_t k = 0; k < 600; ++k) kf.observe(tracker.sample(k));
  // 1/60 s is not exact in picoseconds; the filter sees the rounded spacing.
  const double dt = (tracker.nominal_time(600) - tracker.nominal_time(599)).to_seconds();
  const ScalarSteadyState ss = scalar_steady_state(std::pow(sigma_deg * units::kRadPerDeg, 2), std::pow(psd_deg * units::kRadPerDeg, 2), dt,
                                                   std::pow(100.0 * units::kRadPerDeg, 2), 599);
  const auto& p = kf.orientation_covariance();
  for (int i = 0; i < 3; ++i) {
    CHECK(p(i, i) == Approx(ss.a).epsilon(1e-9));
    CHECK(p(i, i + 3) == Approx(ss.b).epsilon(1e-9));
    CHECK(p(i + 3, i + 3) == Approx(ss.c).epsilon(1e-9));
  }
  // Axes do not couple.
  CHECK(p(0, 1) == 0.0);
}

TEST_CASE("Kalman holds a noisy still head steadier than its samples, for an hour without drift", "[kalman]") {
  const double sigma_deg = 0.1, psd_deg = 100.0;
  const Pose truth{{0.0, 1.6, 0.0}, quat_from_yaw_pitch(0.7, 0.1)};
  const StillMotion still(truth);
  Tracker tracker(tracker_params(60, sigma_deg, 0.0), still, RandomStream(5, "tracker"));
  KalmanPredictor kf(params_with_noise(sigma_deg, 0.0, psd_deg));
  const int64_t per_block = 36000;  // ten minutes at 60 Hz
  double raw_sq[6] = {}, est_sq[6] = {};
  glm::dvec3 rate_sum{0.0};
  for (int block = 0; block < 6; ++block)
    for (int64_t i = 0; i < per_block; ++i) {
      const TrackerSample s = tracker.sample(block * per_block + i);
      kf.observe(s);
      if (block == 0 && i < 600) continue;  // let the filter settle
      const MotionEstimate e = *kf.estimate();
      raw_sq[block] += std::pow(angle_between(s.pose.orientation, truth.orientation), 2);
      est_sq[block] += std::pow(angle_between(e.pose.orientation, truth.orientation), 2);
      rate_sum += e.angular_velocity_rad_s;
    }
  const double dt = 1.0 / 60.0;
  const ScalarSteadyState ss =
      scalar_steady_state(std::pow(sigma_deg * units::kRadPerDeg, 2), std::pow(psd_deg * units::kRadPerDeg, 2), dt, std::pow(100.0 * units::kRadPerDeg, 2), 5000);
  // Three axes: the mean squared angle is 3x the per-axis variance.
  for (int block = 0; block < 6; ++block) {
    const int64_t n = block == 0 ? per_block - 600 : per_block;
    const double raw_rms = std::sqrt(raw_sq[block] / static_cast<double>(n));
    const double est_rms = std::sqrt(est_sq[block] / static_cast<double>(n));
    INFO("block " << block << ": raw " << raw_rms / units::kRadPerDeg << " deg, filtered " << est_rms / units::kRadPerDeg << " deg");
    CHECK(raw_rms == Approx(std::sqrt(3.0) * sigma_deg * units::kRadPerDeg).epsilon(0.02));
    // The actual error of the filter on a still head (not its belief P, which
    // allows for motion that never happens), within sampling error; the
    // last ten minutes are as good as the first: nothing drifts.
    CHECK(est_rms == Approx(std::sqrt(3.0 * ss.A)).epsilon(0.03));
    CHECK(est_rms < 0.95 * raw_rms);
  }
  // The mean rate estimate is zero to within its sampling error
  // (sqrt(C / n_eff), with n_eff well above 1000).
  const glm::dvec3 mean_rate = rate_sum / static_cast<double>(6 * per_block - 600);
  CHECK(glm::length(mean_rate) < 3.0 * std::sqrt(ss.C / 1000.0));
  CHECK(std::abs(glm::length(kf.estimate()->pose.orientation) - 1.0) < 1e-15);
}

TEST_CASE("Kalman tracks a constant rate without lag, with and without noise", "[kalman]") {
  const glm::dvec3 axis{0.0, 1.0, 0.0};
  const ConstantAngularVelocity spin(Pose{{0.0, 1.6, 0.0}, glm::dquat{1, 0, 0, 0}}, axis, 120.0);
  SECTION("noise-free samples: the rate converges to the truth and predictions are exact") {
    Tracker tracker(tracker_params(60, 0.0, 0.0), spin, RandomStream(1, "tracker"));
    KalmanPredictor kf(params_with_noise(0.0, 0.0));
    for (int64_t k = 0; k < 600; ++k) kf.observe(tracker.sample(k));
    const MotionEstimate e = *kf.estimate();
    CHECK(glm::length(e.angular_velocity_rad_s - axis * (120.0 * units::kRadPerDeg)) < 1e-9);
    const Time target = e.at + Time::ms(100);
    CHECK(angle_between(extrapolate(e, target).orientation, spin.pose_at(target).orientation) < 1e-9);
  }
  SECTION("noisy samples: the prediction error has zero mean along the turn") {
    Tracker tracker(tracker_params(60, 0.2, 0.0), spin, RandomStream(2, "tracker"));
    KalmanPredictor kf(params_with_noise(0.2, 0.0));
    double signed_sum = 0.0, sq_sum = 0.0;
    int64_t n = 0;
    for (int64_t k = 0; k < 20000; ++k) {
      kf.observe(tracker.sample(k));
      if (k < 600) continue;
      const MotionEstimate e = *kf.estimate();
      const Time target = e.at + Time::ms(40);
      const glm::dvec3 err = rotation_vector_between(spin.pose_at(target).orientation, extrapolate(e, target).orientation);
      signed_sum += glm::dot(err, axis);
      sq_sum += glm::dot(err, axis) * glm::dot(err, axis);
      ++n;
    }
    const double mean = signed_sum / n, rms = std::sqrt(sq_sum / n);
    // A lagging filter would show a mean of about -rate x lag; an unbiased
    // one a mean within a few standard errors (errors stay correlated over
    // ~20 samples, so n_eff ~ n / 20).
    CHECK(std::abs(mean) < 4.0 * rms / std::sqrt(n / 20.0));
  }
}

TEST_CASE("Kalman hard cases: sign flips, half turns, microsecond spacing, jitter", "[kalman]") {
  const glm::dvec3 axis = glm::normalize(glm::dvec3{0.2, 1.0, 0.0});
  SECTION("a sign flip changes nothing") {
    const ConstantAngularVelocity spin(Pose{}, axis, 90.0);
    KalmanPredictor plain(params_with_noise(0.05, 0.001)), flipped(params_with_noise(0.05, 0.001));
    for (int k = 0; k < 50; ++k) {
      TrackerSample s;
      s.index = k;
      s.measured_at = Time::ms(10) * k;
      s.pose = spin.pose_at(s.measured_at);
      plain.observe(s);
      if (k % 3 == 1) s.pose.orientation = -s.pose.orientation;
      flipped.observe(s);
    }
    CHECK(angle_between(plain.estimate()->pose.orientation, flipped.estimate()->pose.orientation) < 1e-15);
    CHECK(glm::length(plain.estimate()->angular_velocity_rad_s - flipped.estimate()->angular_velocity_rad_s) < 1e-13);
  }
  SECTION("a 180 degree turn within one interval gives a bounded, unit estimate") {
    KalmanPredictor kf(params_with_noise(0.05, 0.001));
    TrackerSample s;
    for (int k = 0; k < 10; ++k) {
      s.index = k;
      s.measured_at = Time::ms(10) * k;
      // Still, then a half turn between samples 4 and 5, then still again.
      s.pose.orientation = k < 5 ? glm::dquat{1, 0, 0, 0} : quat_from_rotation_vector(axis * units::kPi);
      kf.observe(s);
      const MotionEstimate e = *kf.estimate();
      CHECK(std::abs(glm::length(e.pose.orientation) - 1.0) < 1e-15);
      CHECK(std::isfinite(glm::length(e.angular_velocity_rad_s)));
      // The largest rate a half turn in 10 ms can suggest is pi / 10 ms.
      CHECK(glm::length(e.angular_velocity_rad_s) <= units::kPi / 0.01 * 1.0001);
    }
    CHECK(min_eigenvalue(kf.orientation_covariance()) > -1e-18);
  }
  SECTION("1 us between samples: the rate comes out right and P stays positive") {
    const ConstantAngularVelocity spin(Pose{}, axis, 200.0);
    KalmanPredictor kf(params_with_noise(0.0, 0.0));
    for (int k = 0; k < 2000; ++k) {
      TrackerSample s;
      s.index = k;
      s.measured_at = Time::s(1) + Time::us(1) * k;
      s.pose = spin.pose_at(s.measured_at);
      kf.observe(s);
    }
    const MotionEstimate e = *kf.estimate();
    // Rounding of a few ulps (<= 1e-15) per sample over 1 us bounds the rate
    // error by ~2e-9 rad/s (the filter averages several differences, doing
    // no worse), so ~2e-9 rad after a 1 s horizon.
    CHECK(glm::length(e.angular_velocity_rad_s - axis * (200.0 * units::kRadPerDeg)) < 3e-9);
    const Time target = e.at + Time::s(1);
    CHECK(angle_between(extrapolate(e, target).orientation, spin.pose_at(target).orientation) < 5e-9);
    CHECK(min_eigenvalue(kf.orientation_covariance()) > -1e-20);
    CHECK(kf.orientation_covariance().allFinite());
  }
  SECTION("jittered intervals: still exact for a constant rate") {
    const ConstantAngularVelocity spin(Pose{}, axis, 150.0);
    TrackerParams tp = tracker_params(90, 0.0, 0.0);
    tp.jitter = Time::ms(4);
    Tracker tracker(tp, spin, RandomStream(9, "tracker"));
    KalmanPredictor kf(params_with_noise(0.0, 0.0));
    for (int64_t k = 0; k < 900; ++k) kf.observe(tracker.sample(k));
    const MotionEstimate e = *kf.estimate();
    CHECK(glm::length(e.angular_velocity_rad_s - axis * (150.0 * units::kRadPerDeg)) < 1e-9);
    CHECK(angle_between(extrapolate(e, e.at + Time::s(1)).orientation, spin.pose_at(e.at + Time::s(1)).orientation) <
          1e-8);
  }
}

TEST_CASE("Kalman position filter follows a walk at constant speed without bias", "[kalman]") {
  WalkParams w;
  w.points_m = {{0.0, 1.6, 0.0}, {1000.0, 1.6, 0.0}};
  w.speed_m_s = 1.0;
  w.face_direction = false;
  const PolylineWalk walk(w);
  const double sigma_m = 0.002;
  Tracker tracker(tracker_params(60, 0.0, sigma_m), walk, RandomStream(4, "tracker"));
  KalmanParams kp = params_with_noise(0.0, sigma_m);
  KalmanPredictor kf(kp);
  const Time horizon = Time::ms(50);
  double speed_sum = 0.0, sq_sum = 0.0;
  int64_t n = 0;
  for (int64_t k = 0; k < 30000; ++k) {
    kf.observe(tracker.sample(k));
    if (k < 600) continue;
    const MotionEstimate e = *kf.estimate();
    speed_sum += e.velocity_m_s.x;
    sq_sum += std::pow(glm::length(extrapolate(e, e.at + horizon).position_m - walk.pose_at(e.at + horizon).position_m), 2);
    ++n;
  }
  // A constant velocity is the model's own motion with no process noise, so
  // the actual error follows the still-head recursion: per axis
  // var = A + 2 h B + h^2 C at horizon h.
  const double h = horizon.to_seconds();
  const ScalarSteadyState ss = scalar_steady_state(sigma_m * sigma_m, std::pow(kp.linear_accel_noise_m_s2_rthz, 2),
                                                   1.0 / 60.0, 1.0, 5000);
  const double per_axis = ss.A + 2 * h * ss.B + h * h * ss.C;
  CHECK(std::sqrt(sq_sum / n) == Approx(std::sqrt(3.0 * per_axis)).epsilon(0.05));
  // No lag: the mean speed is 1 m/s within a few standard errors (n_eff ~ n / 20).
  CHECK(std::abs(speed_sum / n - 1.0) < 4.0 * std::sqrt(ss.C / (n / 20.0)));
}

TEST_CASE("Kalman parameters are checked", "[kalman]") {
  KalmanParams p;
  p.angular_accel_noise_deg_s2_rthz = 0.0;
  CHECK_THROWS_AS(KalmanPredictor(p), std::invalid_argument);
  p = KalmanParams{};
  p.initial_speed_m_s = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(KalmanPredictor(p), std::invalid_argument);
  p = KalmanParams{};
  p.measurement_covariance(3, 3) = -1e-6;
  CHECK_THROWS_AS(KalmanPredictor(p), std::invalid_argument);
}
