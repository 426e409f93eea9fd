#include "latsim/tracker/pose.hpp"

#include <cmath>

#include <glm/geometric.hpp>

namespace latsim::tracker {

Pose eye_pose(const Pose& head, int eye, double ipd_m, bool stereo) {
  if (!stereo) return head;
  const double offset = (eye == 0 ? -0.5 : 0.5) * ipd_m;
  Pose p = head;
  p.position_m += head.orientation * glm::dvec3(offset, 0.0, 0.0);
  return p;
}

double angle_between(const glm::dquat& q1, const glm::dquat& q2) {
  const glm::dquat d = glm::conjugate(q1) * q2;
  const double vec_norm = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  // |w| folds q and -q together, so the answer is always the short arc.
  return 2.0 * std::atan2(vec_norm, std::abs(d.w));
}

glm::dquat slerp_short(const glm::dquat& q1, const glm::dquat& q2, double t) {
  const glm::dquat target = same_hemisphere(q2, q1);
  // Interpolate the relative rotation d = q1^-1 q2 as exp(t log d): only the
  // half angle is scaled, and the axis comes from vec(d) directly, so nearly
  // equal inputs never divide by a vanishing sine.
  const glm::dquat d = glm::conjugate(q1) * target;
  const glm::dvec3 v{d.x, d.y, d.z};
  const double vec_norm = glm::length(v);
  if (vec_norm == 0.0) return glm::normalize(q1);
  const double half_angle = std::atan2(vec_norm, d.w);
  const double scaled = t * half_angle;
  const glm::dvec3 axis = v / vec_norm;
  const glm::dquat step{std::cos(scaled), std::sin(scaled) * axis.x, std::sin(scaled) * axis.y,
                        std::sin(scaled) * axis.z};
  return glm::normalize(q1 * step);
}

glm::dquat quat_from_rotation_vector(const glm::dvec3& r_rad) {
  const double angle = glm::length(r_rad);
  if (angle == 0.0) return glm::dquat{1.0, 0.0, 0.0, 0.0};
  const double s = std::sin(0.5 * angle) / angle;
  return glm::dquat{std::cos(0.5 * angle), s * r_rad.x, s * r_rad.y, s * r_rad.z};
}

glm::dvec3 rotation_vector_of(const glm::dquat& q) {
  const glm::dquat c = q.w < 0.0 ? -q : q;
  const glm::dvec3 v{c.x, c.y, c.z};
  const double vec_norm = glm::length(v);
  if (vec_norm == 0.0) return glm::dvec3{0.0};
  // v / |v| is a unit axis however small |v| is; the angle comes from atan2.
  return v * (2.0 * std::atan2(vec_norm, c.w) / vec_norm);
}

glm::dvec3 rotation_vector_between(const glm::dquat& from, const glm::dquat& to) {
  return rotation_vector_of(to * glm::conjugate(from));
}

glm::dquat quat_from_yaw_pitch(double yaw_rad, double pitch_rad) {
  const glm::dquat yaw{std::cos(0.5 * yaw_rad), 0.0, std::sin(0.5 * yaw_rad), 0.0};
  const glm::dquat pitch{std::cos(0.5 * pitch_rad), std::sin(0.5 * pitch_rad), 0.0, 0.0};
  return yaw * pitch;
}

glm::dvec3 forward_of(const glm::dquat& orientation) {
  return orientation * glm::dvec3{0.0, 0.0, -1.0};
}

double yaw_of(const glm::dquat& orientation) {
  const glm::dvec3 f = forward_of(orientation);
  return std::atan2(-f.x, -f.z);
}

double pitch_of(const glm::dquat& orientation) {
  const glm::dvec3 f = forward_of(orientation);
  return std::atan2(f.y, std::hypot(f.x, f.z));
}

glm::dquat same_hemisphere(const glm::dquat& q, const glm::dquat& reference) {
  return glm::dot(q, reference) < 0.0 ? -q : q;
}

}  // namespace latsim::tracker
