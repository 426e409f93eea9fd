// Head poses and the quaternion helpers every tracker model needs.
//
// Frames. The world frame is right-handed with y up. The head frame follows
// the OpenGL camera convention: x to the right, y up, -z forward (the viewing
// direction). A pose's orientation is the rotation that maps head-frame
// vectors to world-frame vectors, and its position is the head-frame origin
// (the point between the eyes) in world metres.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace latsim::tracker {

/// Where the head is and which way it looks (head frame -> world frame).
struct Pose {
  glm::dvec3 position_m{0.0, 0.0, 0.0};
  glm::dquat orientation{1.0, 0.0, 0.0, 0.0};
};

/// The pose of one eye of a head: stereo eyes sit ipd_m / 2 either side of
/// the head origin along the head's x axis (eye 0, the left, at -x), looking
/// the same way as the head; mono (and any eye of a mono head) is the head
/// pose itself.
Pose eye_pose(const Pose& head, int eye, double ipd_m, bool stereo);

/// The rotation angle in radians, in [0, pi], between two unit quaternions,
/// short arc (q and -q are the same orientation). Computed as
/// 2*atan2(|vec(q1^-1 q2)|, |w|), which keeps full relative precision for tiny
/// angles where acos of a dot product loses half the digits.
double angle_between(const glm::dquat& q1, const glm::dquat& q2);

/// Spherical interpolation along the short arc from q1 (t = 0) to q2 (t = 1).
/// Robust to sign flips and to nearly equal inputs (no division by a small
/// sine); the result is unit length.
glm::dquat slerp_short(const glm::dquat& q1, const glm::dquat& q2, double t);

/// The rotation exp(r): angle |r| radians about r/|r| (identity for r = 0).
glm::dquat quat_from_rotation_vector(const glm::dvec3& r_rad);

/// The rotation vector of q, log(q): angle in [0, pi] times the unit axis, on
/// the short arc (q and -q give the same vector). Computed from vec(q) and
/// 2*atan2(|vec|, |w|) like angle_between, so tiny rotations keep full
/// relative precision; the inverse of quat_from_rotation_vector for angles
/// below pi.
glm::dvec3 rotation_vector_of(const glm::dquat& q);

/// The world-frame rotation vector r with exp(r) * from = to (short arc):
/// rotation_vector_of(to * from^-1). A head turning at angular velocity w
/// (world axes) for dt seconds moves by r = w * dt.
glm::dvec3 rotation_vector_between(const glm::dquat& from, const glm::dquat& to);

/// Orientation looking with the given heading and elevation: yaw about the
/// world y axis (positive turns left, towards -x), then pitch about the
/// head's x axis (positive looks up). No roll.
glm::dquat quat_from_yaw_pitch(double yaw_rad, double pitch_rad);

/// The viewing direction (head -z) in world coordinates.
glm::dvec3 forward_of(const glm::dquat& orientation);

/// Heading of the viewing direction, the inverse of quat_from_yaw_pitch's yaw:
/// atan2(-f.x, -f.z), in (-pi, pi].
double yaw_of(const glm::dquat& orientation);

/// Elevation of the viewing direction above the horizontal plane, in [-pi/2, pi/2].
double pitch_of(const glm::dquat& orientation);

/// q or -q, whichever lies on the same hemisphere as `reference` (dot >= 0),
/// so consecutive samples of a rotating head do not jump by a sign.
glm::dquat same_hemisphere(const glm::dquat& q, const glm::dquat& reference);

}  // namespace latsim::tracker
