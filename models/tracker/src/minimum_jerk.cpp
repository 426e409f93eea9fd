#include "latsim/tracker/minimum_jerk.hpp"
#include "latsim/units/units.hpp"

#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace latsim::tracker {

MinimumJerkMotion::MinimumJerkMotion(MinimumJerkParams params) : params_(params) {
  const double norm = glm::length(params.axis);
  if (!(norm > 0.0) || !std::isfinite(norm))
    throw std::invalid_argument("minimum-jerk motion needs a non-zero, finite rotation axis");
  if (params.duration <= des::Time::zero()) throw std::invalid_argument("minimum-jerk duration must be positive");
  if (params.rest < des::Time::zero()) throw std::invalid_argument("minimum-jerk rest must not be negative");
  if (params.delay < des::Time::zero()) throw std::invalid_argument("minimum-jerk delay must not be negative");
  if (!std::isfinite(params.amplitude_deg)) throw std::invalid_argument("minimum-jerk amplitude must be finite");
  axis_ = params.axis / norm;
}

double MinimumJerkMotion::profile(double tau) {
  if (tau <= 0.0) return 0.0;
  if (tau >= 1.0) return 1.0;
  // Horner form of 10τ³ − 15τ⁴ + 6τ⁵.
  return tau * tau * tau * (10.0 + tau * (-15.0 + 6.0 * tau));
}

double MinimumJerkMotion::angle_deg_at(des::Time t) const {
  if (t <= params_.delay + params_.rest) return 0.0;
  const des::Time period = params_.rest + params_.duration;
  const des::Time since_first = t - params_.delay - params_.rest;
  const int64_t k = since_first / period;        // movement under way or last finished
  const des::Time into = since_first % period;   // time since movement k started
  const double tau = into >= params_.duration ? 1.0 : into.to_seconds() / params_.duration.to_seconds();
  const double a = params_.amplitude_deg;
  if (!params_.alternate) return a * (static_cast<double>(k) + profile(tau));
  // Even movements go out from the start, odd ones come back.
  return (k % 2 == 0) ? a * profile(tau) : a * (1.0 - profile(tau));
}

Pose MinimumJerkMotion::pose_at(des::Time t) const {
  // Whole turns are removed first so that a long same-way run keeps precision.
  const double turned_deg = std::fmod(angle_deg_at(t), 360.0);
  Pose p = params_.start;
  p.orientation = quat_from_rotation_vector(axis_ * (turned_deg * units::kRadPerDeg)) * params_.start.orientation;
  return p;
}

}  // namespace latsim::tracker
