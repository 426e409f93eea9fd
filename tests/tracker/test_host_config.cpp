// Host view computation.
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/geometric.hpp>

#include "latsim/tracker/host.hpp"

using namespace latsim::tracker;
using latsim::des::Time;

namespace {

TrackerSample head_at(Pose pose) {
  TrackerSample s;
  s.index = 3;
  s.pose = pose;
  return s;
}

}  // namespace

TEST_CASE("stereo eyes are ipd apart along the head's x axis", "[host]") {
  const Pose head{{1.0, 1.7, -2.0}, quat_from_yaw_pitch(0.6, -0.2)};
  const HostFrame f = compute_views(head_at(head), 0.064, true);
  CHECK(f.stereo);
  CHECK(f.sample.index == 3);
  const glm::dvec3 sep = f.right.pose.position_m - f.left.pose.position_m;
  CHECK(glm::length(sep) == Approx(0.064).epsilon(1e-12));
  const glm::dvec3 head_x = head.orientation * glm::dvec3{1.0, 0.0, 0.0};
  CHECK(glm::dot(glm::normalize(sep), head_x) == Approx(1.0).epsilon(1e-12));
  CHECK(glm::length(0.5 * (f.left.pose.position_m + f.right.pose.position_m) - head.position_m) < 1e-12);
  // The view matrix takes the eye to the origin and its forward to -z.
  const glm::dvec4 eye = f.left.view * glm::dvec4(f.left.pose.position_m, 1.0);
  CHECK(glm::length(glm::dvec3(eye)) < 1e-12);
  const glm::dvec4 ahead = f.left.view * glm::dvec4(f.left.pose.position_m + forward_of(head.orientation), 1.0);
  CHECK(ahead.z == Approx(-1.0).epsilon(1e-12));
  CHECK(std::abs(ahead.x) < 1e-12);
}

TEST_CASE("mono views are both the head pose", "[host]") {
  const Pose head{{0.0, 1.5, 0.0}, quat_from_yaw_pitch(-1.0, 0.1)};
  const HostFrame f = compute_views(head_at(head), 0.064, false);
  CHECK_FALSE(f.stereo);
  CHECK(f.left.pose.position_m == head.position_m);
  CHECK(f.right.pose.position_m == head.position_m);
  CHECK(f.left.view == f.right.view);
}
