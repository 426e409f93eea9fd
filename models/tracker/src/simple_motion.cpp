// StillMotion lives in the header; this file holds the two analytic sources.
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "latsim/tracker/motion_source.hpp"
#include "latsim/units/units.hpp"

namespace latsim::tracker {

namespace {


// sin(2 pi (f t) + phase) with the whole cycles of f*t removed first, so the
// argument stays small and hours-long runs keep their precision.
double sine_at(double frequency_hz, des::Time t, double phase_rad) {
  const double cycles = frequency_hz * t.to_seconds();
  const double fraction = cycles - std::floor(cycles);
  return std::sin(2.0 * units::kPi * fraction + phase_rad);
}

}  // namespace

ConstantAngularVelocity::ConstantAngularVelocity(Pose start, glm::dvec3 axis, double rate_deg_s)
    : start_(start), rate_deg_s_(rate_deg_s) {
  const double norm = glm::length(axis);
  if (!(norm > 0.0) || !std::isfinite(norm))
    throw std::invalid_argument("constant angular velocity needs a non-zero, finite rotation axis");
  if (!std::isfinite(rate_deg_s)) throw std::invalid_argument("angular rate must be finite");
  axis_ = axis / norm;
}

Pose ConstantAngularVelocity::pose_at(des::Time t) const {
  // Reduce the angle modulo one full turn in degrees before converting: the
  // orientation is periodic in 360 degrees, and sin/cos of a small argument
  // stay accurate after hours of spinning.
  const double turned_deg = std::fmod(rate_deg_s_ * t.to_seconds(), 360.0);
  Pose p = start_;
  p.orientation = quat_from_rotation_vector(axis_ * (turned_deg * units::kRadPerDeg)) * start_.orientation;
  return p;
}

SinusoidalMotion::SinusoidalMotion(SinusoidParams params) : params_(params) {
  if (!(params.yaw_frequency_hz >= 0.0) || !(params.pitch_frequency_hz >= 0.0))
    throw std::invalid_argument("sinusoid frequencies must be non-negative");
}

bool SinusoidalMotion::is_still() const {
  const bool yaw_still = params_.yaw_amplitude_deg == 0.0 || params_.yaw_frequency_hz == 0.0;
  const bool pitch_still = params_.pitch_amplitude_deg == 0.0 || params_.pitch_frequency_hz == 0.0;
  return yaw_still && pitch_still;
}

double SinusoidalMotion::yaw_rad_at(des::Time t) const {
  return params_.yaw_amplitude_deg * units::kRadPerDeg *
         sine_at(params_.yaw_frequency_hz, t, params_.yaw_phase_deg * units::kRadPerDeg);
}

double SinusoidalMotion::pitch_rad_at(des::Time t) const {
  return params_.pitch_amplitude_deg * units::kRadPerDeg *
         sine_at(params_.pitch_frequency_hz, t, params_.pitch_phase_deg * units::kRadPerDeg);
}

Pose SinusoidalMotion::pose_at(des::Time t) const {
  return Pose{params_.position_m, quat_from_yaw_pitch(yaw_rad_at(t), pitch_rad_at(t))};
}

}  // namespace latsim::tracker
