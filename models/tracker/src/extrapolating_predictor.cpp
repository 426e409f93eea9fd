#include "latsim/tracker/extrapolating_predictor.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace latsim::tracker {

namespace {

double seconds_between(const TrackerSample& a, const TrackerSample& b) {
  return (b.measured_at - a.measured_at).to_seconds();
}

}  // namespace

ExtrapolatingPredictor::ExtrapolatingPredictor(int order) : order_(order) {
  if (order < 0 || order > 2)
    throw std::invalid_argument("extrapolation order must be 0, 1 or 2 (got " + std::to_string(order) + ")");
}

PredictorKind ExtrapolatingPredictor::kind() const {
  if (order_ == 0) return PredictorKind::None;
  return order_ == 1 ? PredictorKind::ConstantVelocity : PredictorKind::ConstantAcceleration;
}

void ExtrapolatingPredictor::observe(const TrackerSample& sample) {
  if (count_ > 0 && sample.measured_at <= recent_[2].measured_at)
    throw std::logic_error("predictor samples must come in increasing measurement time (sample " +
                           std::to_string(sample.index) + " is not later than sample " +
                           std::to_string(recent_[2].index) + ")");
  recent_[0] = recent_[1];
  recent_[1] = recent_[2];
  recent_[2] = sample;
  if (count_ < 3) ++count_;
  update_estimate();
}

void ExtrapolatingPredictor::update_estimate() {
  const TrackerSample& s2 = recent_[2];
  MotionEstimate e;
  e.at = s2.measured_at;
  e.pose = s2.pose;
  const int usable = std::min(order_, count_ - 1);
  if (usable >= 1) {
    const TrackerSample& s1 = recent_[1];
    const double dt12 = seconds_between(s1, s2);
    const glm::dvec3 w12 = rotation_vector_between(s1.pose.orientation, s2.pose.orientation) / dt12;
    const glm::dvec3 v12 = (s2.pose.position_m - s1.pose.position_m) / dt12;
    e.angular_velocity_rad_s = w12;
    e.velocity_m_s = v12;
    if (usable == 2) {
      const TrackerSample& s0 = recent_[0];
      const double dt01 = seconds_between(s0, s1);
      const glm::dvec3 w01 = rotation_vector_between(s0.pose.orientation, s1.pose.orientation) / dt01;
      const glm::dvec3 v01 = (s1.pose.position_m - s0.pose.position_m) / dt01;
      // The two mean rates belong to the interval midpoints, (dt01 + dt12) / 2 apart.
      const double mid_gap = 0.5 * (dt01 + dt12);
      e.angular_acceleration_rad_s2 = (w12 - w01) / mid_gap;
      e.acceleration_m_s2 = (v12 - v01) / mid_gap;
      e.angular_velocity_rad_s = w12 + e.angular_acceleration_rad_s2 * (0.5 * dt12);
      e.velocity_m_s = v12 + e.acceleration_m_s2 * (0.5 * dt12);
    }
  }
  estimate_ = e;
}

}  // namespace latsim::tracker
