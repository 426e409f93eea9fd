#include "latsim/renderer/cube_map.hpp"
#include "latsim/renderer/scene_generators.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace latsim::renderer;

TEST_CASE("Cube lookup of a texel-centre direction returns that texel") {
  constexpr int kN = 8;
  CubeMap cube({0, 0, 0}, kN, glm::vec3(0.0f));
  for (int f = 0; f < CubeMap::kFaceCount; ++f) {
    for (int j = 0; j < kN; ++j) {
      for (int i = 0; i < kN; ++i) cube.texel(f, i, j).colour = glm::vec3(f, i, j);
    }
  }
  for (int f = 0; f < CubeMap::kFaceCount; ++f) {
    for (int j = 0; j < kN; ++j) {
      for (int i = 0; i < kN; ++i) CHECK(cube.lookup(cube.texel_direction(f, i, j) * 3.0).colour == glm::vec3(f, i, j));
    }
  }
  // Major axes land on the OpenGL faces.
  CHECK(cube.lookup({1, 0.1, 0.2}).colour.x == 0.0f);
  CHECK(cube.lookup({-1, 0.1, 0.2}).colour.x == 1.0f);
  CHECK(cube.lookup({0.1, 1, 0.2}).colour.x == 2.0f);
  CHECK(cube.lookup({0.1, -1, 0.2}).colour.x == 3.0f);
  CHECK(cube.lookup({0.1, 0.2, 1}).colour.x == 4.0f);
  CHECK(cube.lookup({0.1, 0.2, -1}).colour.x == 5.0f);
  CHECK_THROWS_AS(cube.lookup({0, 0, 0}), std::invalid_argument);
  CHECK_THROWS_AS(CubeMap({0, 0, 0}, 0, glm::vec3(0.0f)), std::invalid_argument);
}

TEST_CASE("Rendered cube matches direct casts at texel centres") {
  const RayCaster caster(make_room());
  const glm::dvec3 eye(0.4, 1.5, 0.5);
  RenderOptions options;
  options.thread_count = 2;
  const CubeMap cube = render_cube(caster, eye, 24, options);
  int mismatches = 0;
  for (int f = 0; f < CubeMap::kFaceCount; ++f) {
    for (int j = 0; j < 24; ++j) {
      for (int i = 0; i < 24; ++i) {
        const glm::dvec3 dir = cube.texel_direction(f, i, j);
        const Hit hit = caster.cast(eye, dir);
        const CubeTexel texel = cube.lookup(dir);
        REQUIRE(hit.hit);
        mismatches += (texel.colour != hit.colour || texel.depth_m != hit.distance_m) ? 1 : 0;
      }
    }
  }
  CHECK(mismatches == 0);
}

TEST_CASE("A cube memory can hold a subset of the objects") {
  const RayCaster caster(make_room());
  const glm::dvec3 eye(0.0, 1.5, 0.0);
  RenderOptions options;
  options.background = glm::vec3(1.0f);
  options.object_mask.assign(caster.scene().object_count(), 0);
  const uint32_t table = caster.scene().find_object("table");
  options.object_mask[table] = 1;
  const CubeMap cube = render_cube(caster, eye, 32, options);
  int hits = 0;
  for (int f = 0; f < CubeMap::kFaceCount; ++f) {
    for (int j = 0; j < 32; ++j) {
      for (int i = 0; i < 32; ++i) {
        const glm::dvec3 dir = cube.texel_direction(f, i, j);
        const CubeTexel& texel = cube.texel(f, i, j);
        const Hit masked = caster.cast(eye, dir, options.object_mask);
        if (std::isinf(texel.depth_m)) {
          CHECK(texel.colour == glm::vec3(1.0f));
          CHECK_FALSE(masked.hit);
        } else {
          ++hits;
          CHECK(masked.object_id == table);
          CHECK(texel.depth_m == masked.distance_m);
        }
      }
    }
  }
  CHECK(hits > 10);
  CHECK(hits < 6 * 32 * 32 / 4);
}
