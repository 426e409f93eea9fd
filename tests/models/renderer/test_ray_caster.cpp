#include "latsim/renderer/mesh_builder.hpp"
#include "latsim/renderer/ray_caster.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

using namespace latsim::renderer;

namespace {

// Big square in the plane z = z_m, facing the origin.
void add_wall(Scene& scene, const char* name, double z_m, const glm::vec3& colour) {
  scene.begin_object(name);
  add_tiled_quad(scene, {-50.0, -50.0, z_m}, {100.0, 0.0, 0.0}, {0.0, 100.0, 0.0}, 0.0,
                 [colour](int, int) { return colour; });
}

}  // namespace

TEST_CASE("Hit distance matches an analytic plane") {
  Scene scene;
  add_wall(scene, "wall", -5.0, glm::vec3(0.8f));
  const RayCaster caster(std::move(scene));
  for (const glm::dvec3 dir : {glm::dvec3(0, 0, -1), glm::dvec3(0.3, -0.2, -1), glm::dvec3(-2, 1.5, -1)}) {
    const glm::dvec3 origin(0.25, 0.5, 1.0);
    const Hit hit = caster.cast(origin, dir);
    REQUIRE(hit.hit);
    // Distance along the unit ray from z = 1 to z = -5 is 6 / |cos| of the angle to -z.
    const double expected = 6.0 * glm::length(dir) / std::fabs(dir.z);
    CHECK(hit.distance_m == Approx(expected).epsilon(1e-5));
    CHECK(hit.object_id == 0);
    CHECK(hit.primitive_id < 2);
  }
  const Hit miss = caster.cast({0, 0, 0}, {0, 0, 1});
  CHECK_FALSE(miss.hit);
  CHECK(std::isinf(miss.distance_m));
  CHECK(miss.object_id == Hit::kNone);
}

TEST_CASE("Hit colour interpolates vertex colours under one fixed light") {
  Scene scene;
  scene.begin_object("rgb");
  scene.add_triangle(Triangle{{glm::vec3(-1, -1, -2), glm::vec3(1, -1, -2), glm::vec3(0, 1, -2)},
                              {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)}});
  const RayCaster caster(std::move(scene));
  const Hit centroid = caster.cast({0, 0, 0}, {0, -1.0 / 3.0, -2});
  REQUIRE(centroid.hit);
  CHECK(centroid.colour.r == Approx(centroid.colour.g).epsilon(1e-4));
  CHECK(centroid.colour.g == Approx(centroid.colour.b).epsilon(1e-4));
  CHECK(centroid.colour.r > 0.1f);
  const Hit near_red = caster.cast({0, 0, 0}, {-0.9, -0.95, -2});
  REQUIRE(near_red.hit);
  CHECK(near_red.colour.r > 5.0f * near_red.colour.g);
  CHECK(near_red.colour.r > 5.0f * near_red.colour.b);
  // The light is fixed in the world, so the same surface point is equally bright from
  // another viewpoint.
  const Hit other_view = caster.cast({0.5, -1.0 / 3.0, 1}, {-0.5, 0, -3});
  CHECK(other_view.colour.r == Approx(centroid.colour.r).epsilon(1e-4));
}

TEST_CASE("Object masks hide objects from rays") {
  Scene scene;
  add_wall(scene, "near", -3.0, glm::vec3(1, 0, 0));
  add_wall(scene, "far", -6.0, glm::vec3(0, 0, 1));
  const RayCaster caster(std::move(scene));
  CHECK(caster.cast({0, 0, 0}, {0, 0, -1}).object_id == 0);
  const Hit hidden = caster.cast({0, 0, 0}, {0, 0, -1}, ObjectMask{0, 1});
  CHECK(hidden.object_id == 1);
  CHECK(hidden.distance_m == Approx(6.0));
  CHECK_FALSE(caster.cast({0, 0, 0}, {0, 0, -1}, ObjectMask{0, 0}).hit);
  CHECK_THROWS_AS(caster.cast({0, 0, 0}, {0, 0, -1}, ObjectMask{1}), std::invalid_argument);

  std::vector<Ray> rays(100, Ray{{0, 0, 0}, {0.01, 0.0, -1.0}});
  std::vector<Hit> hits(rays.size());
  RenderOptions options;
  options.object_mask = {0, 1};
  options.thread_count = 2;
  caster.cast_rays(rays, hits, options);
  for (const Hit& h : hits) CHECK(h.object_id == 1);
}

TEST_CASE("rays Embree cannot trace are refused with an error instead of ending the process") {
  // Embree's ray.valid() asserts |component| <= 1.844e18 and finite values; a
  // head placed at 1e20 m used to abort the run inside Embree.
  Scene scene;
  add_wall(scene, "wall", -5.0, glm::vec3(0.8f));
  const RayCaster caster(std::move(scene));
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const glm::dvec3 origin : {glm::dvec3(1e20, 0, 0), glm::dvec3(0, -2e18, 0), glm::dvec3(inf, 0, 0),
                                  glm::dvec3(0, 0, nan)})
    CHECK_THROWS_WITH(caster.cast(origin, {0, 0, -1}), Catch::Contains("cannot trace a ray"));
  for (const glm::dvec3 dir : {glm::dvec3(0, 0, 0), glm::dvec3(nan, 0, -1), glm::dvec3(inf, 0, -1)})
    CHECK_THROWS_WITH(caster.cast({0, 0, 0}, dir), Catch::Contains("cannot trace a ray"));
  // The batch paths check every ray too.
  std::vector<Ray> rays{{{0, 0, 0}, {0, 0, -1}}, {{1e20, 0, 0}, {0, 0, -1}}};
  std::vector<Hit> hits(rays.size());
  CHECK_THROWS_WITH(caster.cast_rays(rays, hits, RenderOptions{}), Catch::Contains("cannot trace a ray"));
  // Far but within the limit still traces (and misses the wall 1e17 m away sideways).
  CHECK_FALSE(caster.cast({1e17, 0, 0}, {0, 0, -1}).hit);
  CHECK(caster.cast({0, 0, 0}, {0, 0, -1}).hit);
}
