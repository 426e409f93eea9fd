// Segmentation of large objects along region boundaries.
#include <catch2/catch.hpp>

#include <map>

#include <glm/geometric.hpp>

#include "latsim/arp/segmentation.hpp"
#include "latsim/renderer/mesh_builder.hpp"
#include "latsim/renderer/scene_generators.hpp"

using namespace latsim;

namespace {

double area_of(const renderer::Scene& scene, uint32_t object) {
  const auto& obj = scene.objects()[object];
  double area = 0.0;
  for (uint32_t t = obj.first_triangle; t < obj.first_triangle + obj.triangle_count; ++t) {
    const auto& p = scene.triangles()[t].position_m;
    area += 0.5 * glm::length(glm::cross(glm::dvec3(p[1]) - glm::dvec3(p[0]), glm::dvec3(p[2]) - glm::dvec3(p[0])));
  }
  return area;
}

// One untiled 10 x 10 m floor quad and a slanted wall, neither aligned to the grid.
renderer::Scene coarse_scene() {
  renderer::Scene scene;
  scene.begin_object("floor");
  renderer::add_tiled_quad(scene, {-5.0, 0.0, -5.0}, {10.0, 0.0, 0.0}, {0.0, 0.0, 10.0}, 0.0,
                           [](int, int) { return glm::vec3(0.5f); });
  scene.begin_object("slanted");
  renderer::add_tiled_quad(scene, {-4.3, 0.0, -3.1}, {7.7, 0.0, 5.3}, {0.0, 2.5, 0.0}, 0.0,
                           [](int, int) { return glm::vec3(0.9f, 0.2f, 0.2f); });
  return scene;
}

}  // namespace

TEST_CASE("segmentation keeps every object's area and puts each piece inside one region") {
  const renderer::Scene scene = coarse_scene();
  const renderer::RegionGrid grid(scene.bounds(), 1.5);
  const arp::SegmentedScene cut = arp::segment_scene(scene, grid);
  REQUIRE(cut.segmented);
  std::map<uint32_t, double> area;
  for (const arp::Segment& seg : cut.segments) {
    REQUIRE(seg.regions.size() == 1);
    area[seg.source_object] += area_of(cut.scene, seg.scene_object);
    renderer::Aabb box = grid.region_bounds(grid.from_linear(seg.regions[0]));
    const auto& obj = cut.scene.objects()[seg.scene_object];
    CHECK(obj.bounds.min_m.x >= box.min_m.x - 1e-5);
    CHECK(obj.bounds.max_m.x <= box.max_m.x + 1e-5);
    CHECK(obj.bounds.min_m.z >= box.min_m.z - 1e-5);
    CHECK(obj.bounds.max_m.z <= box.max_m.z + 1e-5);
  }
  CHECK(area[0] == Approx(area_of(scene, 0)).epsilon(1e-5));
  CHECK(area[1] == Approx(area_of(scene, 1)).epsilon(1e-5));
  CHECK(cut.segments.size() > 20);
}

TEST_CASE("neighbouring segments share bit-identical vertices on region boundaries") {
  const renderer::Scene scene = coarse_scene();
  const renderer::RegionGrid grid(scene.bounds(), 1.5);
  const arp::SegmentedScene cut = arp::segment_scene(scene, grid);
  REQUIRE(cut.shared_vertices.size() > 20);
  for (const arp::SharedVertex& v : cut.shared_vertices) {
    const auto& a = cut.segments[v.segment_a];
    const auto& b = cut.segments[v.segment_b];
    CHECK(a.regions != b.regions);
    // The vertex is on the boundary of both regions (distance zero to each square).
    for (int r : {a.regions[0], b.regions[0]}) {
      const renderer::Aabb box = grid.region_bounds(grid.from_linear(r));
      CHECK(v.position_m.x >= box.min_m.x - 1e-5);
      CHECK(v.position_m.x <= box.max_m.x + 1e-5);
      CHECK(v.position_m.z >= box.min_m.z - 1e-5);
      CHECK(v.position_m.z <= box.max_m.z + 1e-5);
    }
  }
}

TEST_CASE("the gallery splits into many more segments than objects, and whole objects stay whole") {
  const renderer::Scene scene = renderer::make_gallery(renderer::GalleryParams{});
  const renderer::RegionGrid grid(scene.bounds(), 2.0);
  const arp::SegmentedScene cut = arp::segment_scene(scene, grid);
  const arp::SegmentedScene whole = arp::whole_objects(scene, grid);
  CHECK(whole.segments.size() == scene.object_count());
  CHECK_FALSE(whole.segmented);
  CHECK(cut.segments.size() > 2 * scene.object_count());
  // Cutting only adds triangles (partitions and frames straddle boundaries) and keeps the area.
  CHECK(cut.scene.triangle_count() > scene.triangle_count());
  double area_in = 0.0;
  double area_out = 0.0;
  for (uint32_t o = 0; o < scene.object_count(); ++o) area_in += area_of(scene, o);
  for (uint32_t o = 0; o < cut.scene.object_count(); ++o) area_out += area_of(cut.scene, o);
  CHECK(area_out == Approx(area_in).epsilon(1e-6));
  // The floor alone covers all 100 regions.
  int floor_pieces = 0;
  for (const auto& seg : cut.segments) floor_pieces += seg.source_object == scene.find_object("floor");
  CHECK(floor_pieces == grid.region_count());
}
