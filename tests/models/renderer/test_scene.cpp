#include "latsim/renderer/region_grid.hpp"
#include "latsim/renderer/scene.hpp"
#include "latsim/renderer/scene_generators.hpp"

#include <catch2/catch.hpp>

#include <string>

using namespace latsim::renderer;

namespace {

bool same_triangles(const Scene& a, const Scene& b) {
  if (a.triangle_count() != b.triangle_count()) return false;
  for (uint32_t i = 0; i < a.triangle_count(); ++i) {
    if (a.triangles()[i].position_m != b.triangles()[i].position_m) return false;
    if (a.triangles()[i].colour != b.triangles()[i].colour) return false;
  }
  return true;
}

int count_objects_with_prefix(const Scene& scene, const std::string& prefix) {
  int n = 0;
  for (const SceneObject& o : scene.objects()) n += o.name.rfind(prefix, 0) == 0 ? 1 : 0;
  return n;
}

}  // namespace

TEST_CASE("Scene keeps objects as contiguous triangle ranges with bounds") {
  Scene scene;
  REQUIRE_THROWS_AS(scene.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1}), SceneError);
  CHECK(scene.begin_object("a") == 0);
  scene.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1});
  CHECK(scene.begin_object("b", true) == 1);
  scene.add_triangle({2, 0, -1}, {3, 0, -1}, {2, 4, -1}, {1, 0, 0});
  scene.add_triangle({2, 0, -1}, {3, 0, -1}, {2, 4, -2}, {1, 0, 0});
  REQUIRE(scene.object_count() == 2);
  CHECK(scene.objects()[1].first_triangle == 1);
  CHECK(scene.objects()[1].triangle_count == 2);
  CHECK(scene.objects()[1].animated);
  CHECK(scene.objects()[0].bounds.max_m == glm::dvec3(1, 1, 0));
  CHECK(scene.objects()[1].bounds.min_m == glm::dvec3(2, 0, -2));
  CHECK(scene.bounds().min_m == glm::dvec3(0, 0, -2));
  CHECK(scene.bounds().max_m == glm::dvec3(3, 4, 0));
  CHECK(scene.find_object("b") == 1);
  CHECK_THROWS_AS(scene.find_object("c"), SceneError);
}

TEST_CASE("Built-in scenes are deterministic and modest in size") {
  CHECK(same_triangles(make_test_pattern(), make_test_pattern()));
  CHECK(same_triangles(make_room(), make_room()));
  CHECK(same_triangles(make_gallery({}), make_gallery({})));
  const Scene room = make_room();
  CHECK(room.triangle_count() > 500);
  CHECK(room.triangle_count() < 4000);
  CHECK(room.bounds().min_m.y == Approx(0.0));
  CHECK(room.bounds().max_m.y == Approx(2.7));
  CHECK(make_test_pattern().find_object("box_2m") != make_test_pattern().find_object("box_9m"));
}

TEST_CASE("Gallery follows its parameters") {
  GalleryParams params;
  params.size_x_m = 20.0;
  params.size_z_m = 16.0;
  params.height_m = 3.0;
  params.partition_count = 3;
  params.frames_per_wall = 2;
  const Scene gallery = make_gallery(params);
  CHECK(gallery.bounds().min_m.x == Approx(-10.0));
  CHECK(gallery.bounds().max_m.z == Approx(8.0));
  CHECK(gallery.bounds().max_m.y == Approx(3.0));
  CHECK(count_objects_with_prefix(gallery, "partition_") == 3);
  // Two frames on each outer wall and on both sides of each partition; frames on
  // partitions are named after them, so count them separately.
  CHECK(count_objects_with_prefix(gallery, "frame_") == 4 * 2 + 3 * 2 * 2);
  CHECK(count_objects_with_prefix(gallery, "frame_partition_") == 3 * 2 * 2);

  // Large objects span several 5 m regions, as the segmentation experiment needs.
  const RegionGrid grid(gallery.bounds(), 5.0);
  CHECK(grid.regions_of(gallery.objects()[gallery.find_object("floor")].bounds).size() == 16);
  CHECK(grid.regions_of(gallery.objects()[gallery.find_object("wall_north")].bounds).size() == 4);
  CHECK(grid.regions_of(gallery.objects()[gallery.find_object("frame_north_0")].bounds).size() <= 2);

  params.partition_count = 5;
  CHECK(count_objects_with_prefix(make_gallery(params), "partition_") == 5);
  params.size_x_m = 0.0;
  CHECK_THROWS_AS(make_gallery(params), std::invalid_argument);
}

TEST_CASE("Gallery tiles put triangle edges on region boundaries") {
  const Scene gallery = make_gallery({});
  const SceneObject& floor = gallery.objects()[gallery.find_object("floor")];
  const RegionGrid grid(gallery.bounds(), 5.0);
  // With 1 m tiles and 5 m regions, no floor triangle straddles a region boundary.
  for (uint32_t k = 0; k < floor.triangle_count; ++k) {
    const Triangle& t = gallery.triangles()[floor.first_triangle + k];
    Aabb box;
    for (const glm::vec3& p : t.position_m) box.extend(glm::dvec3(p));
    CHECK(grid.regions_of(box).size() == 1);
  }
}
