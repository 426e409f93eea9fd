#include "latsim/renderer/camera.hpp"
#include "latsim/units/units.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace units = latsim::units;

using namespace latsim::renderer;

namespace {

glm::dquat yaw_pitch_roll(double yaw, double pitch, double roll) {
  return glm::angleAxis(yaw, glm::dvec3(0, 1, 0)) * glm::angleAxis(pitch, glm::dvec3(1, 0, 0)) *
         glm::angleAxis(roll, glm::dvec3(0, 0, 1));
}

}  // namespace

TEST_CASE("Camera follows the OpenGL head frame with row 0 at the top") {
  const Camera camera(90.0, 64, 48);
  const glm::dquat identity(1, 0, 0, 0);
  const glm::dvec3 centre = camera.ray_direction(32.0, 24.0, identity);
  CHECK(centre.x == Approx(0.0).margin(1e-12));
  CHECK(centre.y == Approx(0.0).margin(1e-12));
  CHECK(centre.z == Approx(-1.0));
  CHECK(camera.pixel_ray(0, 0, identity).y > 0.0);
  CHECK(camera.pixel_ray(0, 0, identity).x < 0.0);
  CHECK(camera.pixel_ray(63, 47, identity).y < 0.0);
  // The left edge of the image is 45 degrees off axis at 90 degrees horizontal FOV.
  const glm::dvec3 left = camera.ray_direction(0.0, 24.0, identity);
  CHECK(std::atan2(-left.x, -left.z) == Approx(units::kPi / 4));
  CHECK(camera.vfov_deg() == Approx(units::rad_to_deg(2.0 * std::atan(0.75))));
  CHECK(camera.focal_px() == Approx(32.0));
  // Yawing the head left (positive about +y) turns the view towards -x.
  const glm::dvec3 turned = camera.ray_direction(32.0, 24.0, glm::angleAxis(0.5, glm::dvec3(0, 1, 0)));
  CHECK(turned.x == Approx(-std::sin(0.5)));
}

TEST_CASE("Projection inverts the pixel ray for any pose") {
  const Camera camera(70.0, 320, 200);
  const latsim::tracker::Pose pose{{1.5, -0.25, 3.0}, yaw_pitch_roll(0.7, -0.3, 0.2)};
  for (int y : {0, 17, 100, 199}) {
    for (int x : {0, 5, 160, 319}) {
      for (double distance_m : {0.3, 2.0, 40.0}) {
        const glm::dvec3 point = pose.position_m + distance_m * camera.pixel_ray(x, y, pose.orientation);
        const auto projected = camera.project(point, pose);
        REQUIRE(projected.has_value());
        CHECK(projected->x == Approx(x + 0.5).margin(1e-9));
        CHECK(projected->y == Approx(y + 0.5).margin(1e-9));
      }
    }
  }
  const glm::dvec3 behind = pose.position_m - camera.pixel_ray(10, 10, pose.orientation);
  CHECK_FALSE(camera.project(behind, pose).has_value());
  CHECK_FALSE(camera.project(pose.position_m, pose).has_value());
}

TEST_CASE("Camera rejects impossible parameters") {
  CHECK_THROWS_AS(Camera(0.0, 10, 10), std::invalid_argument);
  CHECK_THROWS_AS(Camera(180.0, 10, 10), std::invalid_argument);
  CHECK_THROWS_AS(Camera(60.0, 0, 10), std::invalid_argument);
}
