// Quaternion helpers: stable angles, short-arc slerp, yaw/pitch conventions.
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/geometric.hpp>

#include "latsim/tracker/pose.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using namespace latsim::tracker;

namespace {

glm::dquat about(const glm::dvec3& axis, double angle_rad) {
  return quat_from_rotation_vector(glm::normalize(axis) * angle_rad);
}

}  // namespace

TEST_CASE("angle_between is exact for large and tiny angles", "[pose]") {
  const glm::dquat base = about({0.3, -1.0, 0.2}, 1.1);
  for (double angle : {2.5, 1.0, 1e-3, 1e-6, 1e-9}) {
    const glm::dquat q = about({1.0, 2.0, -0.5}, angle) * base;
    CHECK(angle_between(base, q) == Approx(angle).epsilon(1e-6));
  }
  // At 1e-12 rad acos(dot) would return 0 or ~1e-8; the atan2 form keeps the
  // magnitude to within round-off of the quaternion product (~1e-16 absolute).
  const glm::dquat q12 = about({0.0, 1.0, 0.0}, 1e-12) * base;
  CHECK(std::abs(angle_between(base, q12) - 1e-12) < 1e-15);
  CHECK(angle_between(base, base) == 0.0);
}

TEST_CASE("angle_between takes the short arc and ignores sign", "[pose]") {
  const glm::dquat a = about({0.0, 0.0, 1.0}, 0.4);
  const glm::dquat b = about({0.0, 0.0, 1.0}, 0.7);
  CHECK(angle_between(a, -b) == Approx(0.3).epsilon(1e-12));
  CHECK(angle_between(a, -a) == 0.0);
  // 350 degrees one way is 10 degrees the other.
  const glm::dquat c = about({0.0, 1.0, 0.0}, units::deg_to_rad(350.0));
  CHECK(angle_between(glm::dquat{1, 0, 0, 0}, c) == Approx(units::deg_to_rad(10.0)).epsilon(1e-12));
  CHECK(angle_between(glm::dquat{1, 0, 0, 0}, about({1, 0, 0}, units::kPi)) ==
        Approx(units::kPi).epsilon(1e-15));
}

TEST_CASE("slerp_short interpolates along the short arc", "[pose]") {
  const glm::dquat a = about({0.2, 1.0, 0.1}, 0.3);
  const glm::dquat b = about({1.0, 0.5, -0.3}, 1.2) * a;
  const double full = angle_between(a, b);
  CHECK(angle_between(slerp_short(a, b, 0.0), a) < 1e-15);
  CHECK(angle_between(slerp_short(a, b, 1.0), b) < 1e-14);
  for (double t : {0.1, 0.25, 0.5, 0.9}) {
    const glm::dquat m = slerp_short(a, b, t);
    CHECK(glm::length(m) == Approx(1.0).epsilon(1e-15));
    CHECK(angle_between(a, m) == Approx(t * full).epsilon(1e-12));
    CHECK(angle_between(m, b) == Approx((1.0 - t) * full).epsilon(1e-12));
    // A sign-flipped end point is the same orientation and gives the same path.
    CHECK(angle_between(slerp_short(a, -b, t), m) < 1e-14);
  }
}

TEST_CASE("slerp_short is robust for nearly equal quaternions", "[pose]") {
  const glm::dquat a = about({0.0, 1.0, 0.0}, 0.8);
  const glm::dquat b = about({1.0, 0.0, 0.0}, 1e-13) * a;
  const glm::dquat m = slerp_short(a, b, 0.5);
  CHECK(std::isfinite(m.w));
  CHECK(glm::length(m) == Approx(1.0).epsilon(1e-15));
  CHECK(std::abs(angle_between(a, m) - 0.5e-13) < 1e-15);
  const glm::dquat same = slerp_short(a, -a, 0.3);
  CHECK(angle_between(same, a) == 0.0);
}

TEST_CASE("yaw and pitch follow the OpenGL camera convention", "[pose]") {
  const double yaw = 0.7;
  const double pitch = -0.4;
  const glm::dquat q = quat_from_yaw_pitch(yaw, pitch);
  CHECK(yaw_of(q) == Approx(yaw).epsilon(1e-14));
  CHECK(pitch_of(q) == Approx(pitch).epsilon(1e-14));
  // Identity looks down -z; positive yaw turns left (towards -x); positive pitch looks up.
  const glm::dvec3 f0 = forward_of(glm::dquat{1, 0, 0, 0});
  CHECK(f0.z == -1.0);
  CHECK(forward_of(quat_from_yaw_pitch(0.5, 0.0)).x < 0.0);
  CHECK(forward_of(quat_from_yaw_pitch(0.0, 0.5)).y > 0.0);
}
