#include "latsim/tracker/optical_reference.hpp"
#include "latsim/units/units.hpp"

#include <cmath>
#include <stdexcept>

namespace latsim::tracker {

OpticalReference::OpticalReference(ReferenceParams params, const MotionSource& motion, des::RandomStream stream)
    : params_(params),
      schedule_(params.clock.phase.value_or(des::Time::zero()),
                des::period_with_rate_error(params.period, params.clock.rate_error_ppm)),
      motion_(motion),
      noise_(stream.substream("noise")) {
  if (params_.latency < des::Time::zero()) throw std::invalid_argument("reference latency is negative");
  if (!(params_.orientation_stddev_deg >= 0.0) || !(params_.position_stddev_m >= 0.0))
    throw std::invalid_argument("reference noise must not be negative");
}

ReferenceFix OpticalReference::fix(int64_t k) {
  ReferenceFix f;
  f.index = k;
  f.measured_at = schedule_.at(k);
  f.available_at = f.measured_at + params_.latency;
  f.pose = motion_.pose_at(f.measured_at);
  if (params_.orientation_stddev_deg > 0.0) {
    const double s = units::deg_to_rad(params_.orientation_stddev_deg);
    const double x = noise_.normal(0.0, s), y = noise_.normal(0.0, s), z = noise_.normal(0.0, s);
    f.pose.orientation = glm::normalize(quat_from_rotation_vector({x, y, z}) * f.pose.orientation);
  }
  if (params_.position_stddev_m > 0.0) {
    const double s = params_.position_stddev_m;
    const double x = noise_.normal(0.0, s), y = noise_.normal(0.0, s), z = noise_.normal(0.0, s);
    f.pose.position_m += glm::dvec3{x, y, z};
  }
  return f;
}

}  // namespace latsim::tracker
