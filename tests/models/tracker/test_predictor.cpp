// Extrapolating predictors (hold, constant velocity, constant acceleration):
// exactness on the motions they model, at any spacing, and the hard cases.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>

#include "latsim/des/random.hpp"
#include "latsim/tracker/extrapolating_predictor.hpp"
#include "latsim/tracker/motion_source.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using namespace latsim::tracker;
using latsim::des::RandomStream;
using latsim::des::Time;

namespace {


TrackerSample sample_at(int64_t index, Time t, const Pose& pose) {
  TrackerSample s;
  s.index = index;
  s.measured_at = t;
  s.ready_at = t;
  s.pose = pose;
  return s;
}

/// Sample times with uniform jitter of up to +-40 % of the nominal period,
/// so neighbouring intervals differ by a factor of up to 2.3.
std::vector<Time> jittered_times(Time start, Time period, int n, uint64_t seed) {
  RandomStream rng(seed, "jitter");
  std::vector<Time> ts;
  for (int k = 0; k < n; ++k)
    ts.push_back(start + period * k + Time::from_seconds(rng.uniform(-0.4, 0.4) * period.to_seconds()));
  return ts;
}

/// The pose of a head whose angle about a fixed axis is a0 + w0 t + a t^2 / 2
/// and whose position is p0 + v0 t + acc t^2 / 2: the motion constant
/// acceleration assumes, written out directly.
struct QuadraticMotion {
  glm::dvec3 axis = glm::normalize(glm::dvec3{0.3, 1.0, -0.2});
  double w0_rad_s = 1.2, a_rad_s2 = -3.5;
  glm::dvec3 p0{0.5, 1.7, -0.3}, v0{0.8, 0.0, -0.4}, acc{-0.6, 0.2, 1.1};
  glm::dquat q0 = quat_from_yaw_pitch(0.4, -0.1);

  Pose at(Time t) const {
    const double s = t.to_seconds();
    return Pose{p0 + v0 * s + acc * (0.5 * s * s), quat_from_rotation_vector(axis * (w0_rad_s * s + 0.5 * a_rad_s2 * s * s)) * q0};
  }
};

double angle_to(const Pose& a, const Pose& b) { return angle_between(a.orientation, b.orientation); }

}  // namespace

TEST_CASE("constant velocity is exact for a constant-rate turn at jittered intervals and a 1 s horizon",
          "[predictor]") {
  // Any axis, not only yaw; the motion source is the reference (exp(rate t axis) q0).
  const ConstantAngularVelocity spin(Pose{{0.1, 1.6, 0.0}, quat_from_yaw_pitch(1.0, 0.2)}, {1.0, 2.0, -0.5}, 137.0);
  ExtrapolatingPredictor cv(1);
  const auto ts = jittered_times(Time::ms(3), Time::us(16667), 40, 7);
  for (size_t k = 0; k < ts.size(); ++k) cv.observe(sample_at(static_cast<int64_t>(k), ts[k], spin.pose_at(ts[k])));
  const MotionEstimate e = *cv.estimate();
  CHECK(glm::length(e.angular_velocity_rad_s) == Approx(137.0 * units::kRadPerDeg).epsilon(1e-12));
  for (Time h : {Time::zero(), Time::ms(5), Time::ms(50), Time::ms(250), Time::s(1)}) {
    // Rounding of the samples (a few 1e-16 in each component over an
    // interval of >= 10 ms) bounds the rate error by ~1e-13 rad/s.
    CHECK(angle_to(extrapolate(e, ts.back() + h), spin.pose_at(ts.back() + h)) < 1e-12);
  }
}

TEST_CASE("constant acceleration is exact for quadratic angle and position at jittered intervals",
          "[predictor]") {
  const QuadraticMotion m;
  const auto ts = jittered_times(Time::ms(5), Time::ms(10), 25, 11);
  ExtrapolatingPredictor ca(2);
  for (size_t k = 0; k < ts.size(); ++k) ca.observe(sample_at(static_cast<int64_t>(k), ts[k], m.at(ts[k])));
  const MotionEstimate e = *ca.estimate();
  CHECK(e.angular_acceleration_rad_s2.x == Approx(m.a_rad_s2 * m.axis.x).epsilon(1e-8));
  CHECK(e.acceleration_m_s2.z == Approx(m.acc.z).epsilon(1e-8));
  for (Time h : {Time::zero(), Time::ms(20), Time::ms(100), Time::s(1)}) {
    const Pose want = m.at(ts.back() + h);
    const Pose got = extrapolate(e, ts.back() + h);
    // Second differences over ~10 ms intervals turn 1e-16 rounding into
    // ~1e-12 rad/s^2; over a 1 s horizon that is far below 1e-9.
    CHECK(angle_to(got, want) < 1e-9);
    CHECK(glm::length(got.position_m - want.position_m) < 1e-9);
  }
  // Constant velocity on the same motion misses by the acceleration term
  // a h^2 / 2 (plus the rate change over the last half interval).
  ExtrapolatingPredictor cv(1);
  for (size_t k = 0; k < ts.size(); ++k) cv.observe(sample_at(static_cast<int64_t>(k), ts[k], m.at(ts[k])));
  CHECK(angle_to(extrapolate(*cv.estimate(), ts.back() + Time::s(1)), m.at(ts.back() + Time::s(1))) > 1.0);
}

TEST_CASE("hold repeats the newest sample whatever the horizon", "[predictor]") {
  const ConstantAngularVelocity spin(Pose{}, {0, 1, 0}, 90.0);
  ExtrapolatingPredictor hold(0);
  CHECK_FALSE(hold.estimate().has_value());
  hold.observe(sample_at(0, Time::ms(0), spin.pose_at(Time::ms(0))));
  hold.observe(sample_at(1, Time::ms(10), spin.pose_at(Time::ms(10))));
  const Pose p = extrapolate(*hold.estimate(), Time::s(1));
  CHECK(angle_to(p, spin.pose_at(Time::ms(10))) == 0.0);
  CHECK(hold.kind() == PredictorKind::None);
}

TEST_CASE("predictors drop their order until enough samples have arrived", "[predictor]") {
  const QuadraticMotion m;
  ExtrapolatingPredictor ca(2);
  ca.observe(sample_at(0, Time::ms(0), m.at(Time::ms(0))));
  CHECK(glm::length(ca.estimate()->angular_velocity_rad_s) == 0.0);
  ca.observe(sample_at(1, Time::ms(10), m.at(Time::ms(10))));
  // Two samples: the mean rate over the interval, no acceleration yet.
  CHECK(glm::length(ca.estimate()->angular_velocity_rad_s) == Approx(std::abs(m.w0_rad_s + m.a_rad_s2 * 0.005)).epsilon(1e-9));
  CHECK(glm::length(ca.estimate()->angular_acceleration_rad_s2) == 0.0);
}

TEST_CASE("a quaternion sign flip between samples changes no prediction", "[predictor]") {
  const QuadraticMotion m;
  for (int order : {1, 2}) {
    ExtrapolatingPredictor plain(order), flipped(order);
    for (int k = 0; k < 6; ++k) {
      const Time t = Time::ms(11) * k;
      TrackerSample s = sample_at(k, t, m.at(t));
      plain.observe(s);
      // Every other sample arrives as -q, the same orientation.
      if (k % 2 == 1) s.pose.orientation = -s.pose.orientation;
      flipped.observe(s);
    }
    const Time target = Time::ms(55) + Time::ms(40);
    const Pose a = extrapolate(*plain.estimate(), target);
    const Pose b = extrapolate(*flipped.estimate(), target);
    CHECK(angle_to(a, b) < 1e-15);
    if (order == 2) CHECK(angle_to(a, m.at(target)) < 1e-9);
  }
}

TEST_CASE("a half turn or more within one sample interval is seen on the short arc", "[predictor]") {
  const glm::dvec3 axis = glm::normalize(glm::dvec3{0.0, 1.0, 0.3});
  const Time period = Time::ms(10);
  for (double step_deg : {179.0, 180.0, 181.0}) {
    INFO("turn per sample " << step_deg << " deg");
    const ConstantAngularVelocity spin(Pose{}, axis, step_deg / period.to_seconds());
    ExtrapolatingPredictor cv(1);
    for (int k = 0; k < 3; ++k) cv.observe(sample_at(k, period * k, spin.pose_at(period * k)));
    const MotionEstimate e = *cv.estimate();
    // Samples cannot tell +181 degrees from -179: the rate is the short arc's.
    const double seen_deg = std::min(step_deg, 360.0 - step_deg);
    CHECK(glm::length(e.angular_velocity_rad_s) * period.to_seconds() == Approx(seen_deg * units::kRadPerDeg).epsilon(1e-12));
    // At whole sample intervals both readings give the same orientation, so
    // the next sample is predicted exactly either way.
    const Pose next = extrapolate(e, period * 3);
    CHECK(std::abs(glm::length(next.orientation) - 1.0) < 1e-15);
    CHECK(angle_to(next, spin.pose_at(period * 3)) < 1e-9);
    // Half an interval ahead the prediction has turned by half the seen step.
    CHECK(angle_to(extrapolate(e, period * 2 + Time::ms(5)), spin.pose_at(period * 2)) ==
          Approx(0.5 * seen_deg * units::kRadPerDeg).epsilon(1e-9));
  }
}

TEST_CASE("microsecond sample spacing keeps constant velocity exact to rounding", "[predictor]") {
  const ConstantAngularVelocity spin(Pose{{0.0, 1.7, 0.0}, quat_from_yaw_pitch(0.3, 0.1)}, {0, 1, 0}, 200.0);
  ExtrapolatingPredictor cv(1), ca(2);
  for (int k = 0; k < 50; ++k) {
    const TrackerSample s = sample_at(k, Time::us(1) * k + Time::s(2), spin.pose_at(Time::us(1) * k + Time::s(2)));
    cv.observe(s);
    ca.observe(s);
  }
  const Time last = Time::s(2) + Time::us(49);
  // Each sample's components carry a few ulps (<= 1e-15) of rounding; over
  // 1 us that is a rate error of up to ~2e-9 rad/s, i.e. ~2e-9 rad after a
  // 1 s horizon. (The turn per sample, 3.5e-6 rad, is found by atan2 of the
  // vector part, without the cancellation of acos.)
  CHECK(angle_to(extrapolate(*cv.estimate(), last + Time::s(1)), spin.pose_at(last + Time::s(1))) < 5e-9);
  // Constant acceleration divides that rounding by dt^2 / 2: ~2e-15 / 1e-12
  // = ~2e-3 rad/s^2 of spurious acceleration, ~1e-3 rad after 1 s. It stays
  // finite and within that bound; at such spacing acceleration is noise.
  const double ca_error = angle_to(extrapolate(*ca.estimate(), last + Time::s(1)), spin.pose_at(last + Time::s(1)));
  CHECK(std::isfinite(ca_error));
  CHECK(ca_error < 5e-3);
}

TEST_CASE("a still head does not drift over an hour of samples", "[predictor]") {
  const Pose still{{0.2, 1.6, -0.1}, quat_from_yaw_pitch(2.0, -0.3)};
  ExtrapolatingPredictor cv(1), ca(2);
  const Time period = Time::us(16667);
  const int64_t n = Time::s(3600) / period;
  for (int64_t k = 0; k < n; ++k) {
    cv.observe(sample_at(k, period * k, still));
    ca.observe(sample_at(k, period * k, still));
  }
  const Time target = period * (n - 1) + Time::s(1);
  // Identical samples give exactly zero rates: nothing accumulates.
  CHECK(angle_to(extrapolate(*cv.estimate(), target), still) == 0.0);
  CHECK(angle_to(extrapolate(*ca.estimate(), target), still) == 0.0);
  CHECK(extrapolate(*ca.estimate(), target).position_m == still.position_m);
}

TEST_CASE("predictor misuse is reported", "[predictor]") {
  CHECK_THROWS_AS(ExtrapolatingPredictor(3), std::invalid_argument);
  ExtrapolatingPredictor cv(1);
  cv.observe(sample_at(0, Time::ms(5), Pose{}));
  CHECK_THROWS_AS(cv.observe(sample_at(1, Time::ms(5), Pose{})), std::logic_error);
  CHECK(predictor_kind("constant_acceleration") == PredictorKind::ConstantAcceleration);
  CHECK_FALSE(predictor_kind("linear").has_value());
  CHECK(predictor_name(PredictorKind::Kalman) == "kalman");
}

TEST_CASE("rotation vectors invert exp on the short arc and keep tiny angles", "[predictor][pose]") {
  const glm::dvec3 r{0.3, -1.1, 0.7};
  const glm::dvec3 back = rotation_vector_of(quat_from_rotation_vector(r));
  CHECK(glm::length(back - r) < 1e-15);
  CHECK(glm::length(rotation_vector_of(-quat_from_rotation_vector(r)) - r) < 1e-15);
  const glm::dvec3 tiny{1e-13, 0.0, -2e-13};
  CHECK(glm::length(rotation_vector_of(quat_from_rotation_vector(tiny)) - tiny) < 1e-28);
  CHECK(rotation_vector_of(glm::dquat{1, 0, 0, 0}) == glm::dvec3{0.0});
  // Past a half turn the short arc goes the other way.
  const glm::dvec3 y{0.0, 1.0, 0.0};
  CHECK(glm::length(rotation_vector_of(quat_from_rotation_vector(y * (200.0 * units::kRadPerDeg))) + y * (160.0 * units::kRadPerDeg)) < 1e-14);
  const glm::dquat a = quat_from_yaw_pitch(0.2, 0.1), b = quat_from_rotation_vector(r) * a;
  CHECK(glm::length(rotation_vector_between(a, b) - r) < 1e-14);
}
