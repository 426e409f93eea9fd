// The eye poses of a head pose (tracker::eye_pose).
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/geometric.hpp>

#include "latsim/tracker/pose.hpp"

using namespace latsim::tracker;

TEST_CASE("stereo eyes are ipd apart along the head's x axis, left at -x", "[pose]") {
  const Pose head{{1.0, 1.7, -2.0}, quat_from_yaw_pitch(0.6, -0.2)};
  const Pose left = eye_pose(head, 0, 0.064, true);
  const Pose right = eye_pose(head, 1, 0.064, true);
  const glm::dvec3 sep = right.position_m - left.position_m;
  CHECK(glm::length(sep) == Approx(0.064).epsilon(1e-12));
  // The head's x axis in world coordinates, from the yaw alone (pitch turns
  // about that axis and leaves it in place): (cos yaw, 0, -sin yaw).
  const glm::dvec3 head_x{std::cos(0.6), 0.0, -std::sin(0.6)};
  CHECK(glm::dot(glm::normalize(sep), head_x) == Approx(1.0).epsilon(1e-12));
  CHECK(glm::length(0.5 * (left.position_m + right.position_m) - head.position_m) < 1e-12);
  // Both eyes look the way the head looks.
  CHECK(angle_between(left.orientation, head.orientation) == 0.0);
  CHECK(angle_between(right.orientation, head.orientation) == 0.0);
}

TEST_CASE("mono eyes are the head pose", "[pose]") {
  const Pose head{{0.0, 1.5, 0.0}, quat_from_yaw_pitch(-1.0, 0.1)};
  for (int eye = 0; eye < 2; ++eye) {
    const Pose p = eye_pose(head, eye, 0.064, false);
    CHECK(p.position_m == head.position_m);
    CHECK(p.orientation == head.orientation);
  }
}
