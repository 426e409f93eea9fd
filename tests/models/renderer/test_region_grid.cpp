#include "latsim/renderer/region_grid.hpp"
#include "latsim/renderer/scene_generators.hpp"

#include <catch2/catch.hpp>

#include <algorithm>

using namespace latsim::renderer;

namespace {

Aabb box(glm::dvec3 lo, glm::dvec3 hi) {
  Aabb b;
  b.extend(lo);
  b.extend(hi);
  return b;
}

// A 20 x 3 x 20 m world from (-10, 0, -10), cut into 5 m columns.
RegionGrid grid5() { return RegionGrid(box({-10, 0, -10}, {10, 3, 10}), 5.0); }

}  // namespace

TEST_CASE("Region grid covers the world with whole regions") {
  const RegionGrid g = grid5();
  CHECK(g.count_x() == 4);
  CHECK(g.count_z() == 4);
  const RegionGrid odd(box({0, 0, 0}, {20, 3, 7}), 3.0);
  CHECK(odd.count_x() == 7);
  CHECK(odd.count_z() == 3);
  CHECK_THROWS_AS(RegionGrid(box({0, 0, 0}, {1, 1, 1}), 0.0), std::invalid_argument);
  CHECK_THROWS_AS(RegionGrid(Aabb{}, 1.0), std::invalid_argument);
}

TEST_CASE("Points map to half-open regions whatever their height") {
  const RegionGrid g = grid5();
  CHECK(g.region_of({-10, 0, -10}) == RegionIndex{0, 0});
  CHECK(g.region_of({-5, 100, 0}) == RegionIndex{1, 2});
  CHECK(g.region_of({-5.000001, -3, -0.000001}) == RegionIndex{0, 1});
  CHECK(g.region_of({9.99, 1, 9.99}) == RegionIndex{3, 3});
  const RegionIndex outside = g.region_of({12, 1, -11});
  CHECK(outside == RegionIndex{4, -1});
  CHECK_FALSE(g.contains(outside));
  CHECK(g.contains({3, 3}));
  for (int i = 0; i < g.region_count(); ++i) CHECK(g.linear_index(g.from_linear(i)) == i);
  CHECK(g.linear_index({2, 1}) == 6);
  CHECK_THROWS_AS(g.linear_index(outside), std::out_of_range);
  const Aabb r = g.region_bounds({1, 2});
  CHECK(r.min_m == glm::dvec3(-5, 0, 0));
  CHECK(r.max_m == glm::dvec3(0, 3, 5));
}

TEST_CASE("Boxes map to every region their extent reaches into") {
  const RegionGrid g = grid5();
  CHECK(g.regions_of(box({-9, 0, -9}, {-1, 1, -6})) == std::vector<RegionIndex>{{0, 0}, {1, 0}});
  // Ending exactly on a boundary does not reach into the next region.
  CHECK(g.regions_of(box({-9, 0, -9}, {-5, 1, -5})) == std::vector<RegionIndex>{{0, 0}});
  // A flat wall lying on a boundary belongs to the region after it, like a point there.
  CHECK(g.regions_of(box({-5, 0, -9}, {-5, 3, -6})) == std::vector<RegionIndex>{{1, 0}});
  CHECK(g.regions_of(box({-12, 0, 6}, {-7, 1, 30})) == std::vector<RegionIndex>{{0, 3}});
  CHECK(g.regions_of(box({11, 0, 0}, {12, 1, 1})).empty());
  // A wall on the far world boundary belongs to the last column, not to none.
  CHECK(g.regions_of(box({10, 0, -9}, {10, 3, -6})) == std::vector<RegionIndex>{{3, 0}});
  CHECK(g.regions_of(box({-10, 0, 10}, {-6, 3, 10})) == std::vector<RegionIndex>{{0, 3}});
  CHECK(g.regions_of(Aabb{}).empty());
  CHECK(g.regions_of(box({-10, 0, -10}, {10, 3, 10})).size() == 16);
}

TEST_CASE("Objects are listed in every region their bounds overlap") {
  const Scene gallery = make_gallery({});
  const RegionGrid g(gallery.bounds(), 5.0);
  const auto lists = g.objects_per_region(gallery);
  REQUIRE(lists.size() == 16);
  const uint32_t floor = gallery.find_object("floor");
  for (const auto& list : lists) CHECK(std::count(list.begin(), list.end(), floor) == 1);
  size_t listed = 0;
  for (const auto& list : lists) listed += list.size();
  size_t expected = 0;
  for (uint32_t id = 0; id < gallery.object_count(); ++id) {
    const auto regions = g.regions_of(gallery.objects()[id].bounds);
    CHECK_FALSE(regions.empty());
    expected += regions.size();
    for (RegionIndex r : regions) {
      const auto& list = lists[static_cast<size_t>(g.linear_index(r))];
      CHECK(std::find(list.begin(), list.end(), id) != list.end());
    }
  }
  CHECK(listed == expected);
}
