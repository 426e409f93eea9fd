// The view-dependent workload: which regions a triangle's screen bounding box
// covers, checked against projections worked out by hand.
#include <catch2/catch.hpp>

#include <glm/gtc/quaternion.hpp>

#include "latsim/pxpl5/view_workload.hpp"

using namespace latsim::pxpl5;

namespace {

// 640 x 480 with a 90 degree horizontal field of view: a point (X, Y, -d) is
// drawn at x = (X / d + 1) 320, y = (1 - Y / (0.75 d)) 240; regions are 128 px.
ViewScreen wide() {
  ViewScreen s;
  s.hfov_deg = 90.0;
  return s;
}

std::vector<int> regions(const WorldTriangle& t, const latsim::tracker::Pose& pose = {}) {
  const ViewBinner binner({}, wide());
  std::vector<int> out;
  binner.regions_of(t, pose, out);
  return out;
}

}  // namespace

TEST_CASE("a triangle in front covers the regions of its screen bounding box", "[pxpl5][view]") {
  // x from 320 to 400, y from 160 to 240: columns 2-3 of row 1.
  CHECK(regions({glm::dvec3(0, 0, -2), glm::dvec3(0.5, 0, -2), glm::dvec3(0, 0.5, -2)}) == std::vector<int>{7, 8});
  // x from 64 to 127.36, y from 32 to 96: region 0 alone.
  CHECK(regions({glm::dvec3(-1.6, 1.3, -2), glm::dvec3(-1.204, 1.3, -2), glm::dvec3(-1.6, 0.9, -2)}) ==
        std::vector<int>{0});
  // ...and just past the column edge (x to 128.64) it also reaches region 1.
  CHECK(regions({glm::dvec3(-1.6, 1.3, -2), glm::dvec3(-1.196, 1.3, -2), glm::dvec3(-1.6, 0.9, -2)}) ==
        std::vector<int>{0, 1});
  // A triangle larger than the screen covers all 5 x 4 regions.
  CHECK(regions({glm::dvec3(-50, -50, -2), glm::dvec3(50, -50, -2), glm::dvec3(0, 80, -2)}).size() == 20);
}

TEST_CASE("triangles outside the view bin nowhere", "[pxpl5][view]") {
  CHECK(regions({glm::dvec3(0, 0, 2), glm::dvec3(0.5, 0, 2), glm::dvec3(0, 0.5, 2)}).empty());      // behind
  CHECK(regions({glm::dvec3(-5, 0, -2), glm::dvec3(-6, 0, -2), glm::dvec3(-5, 1, -2)}).empty());    // left
  CHECK(regions({glm::dvec3(0, 3, -2), glm::dvec3(1, 3, -2), glm::dvec3(0, 4, -2)}).empty());       // above
}

TEST_CASE("bounding boxes are conservative at the corners of the view", "[pxpl5][view]") {
  // Corners beyond different planes (left only, top only, both): the triangle
  // passes just outside the top-left corner of the screen, but its box (x from
  // -32 to 16, y from -16 to 16) overlaps it, so it is binned into region 0.
  CHECK(regions({glm::dvec3(-2.2, 1.4, -2), glm::dvec3(-1.9, 1.6, -2), glm::dvec3(-2.2, 1.6, -2)}) ==
        std::vector<int>{0});
}

TEST_CASE("a triangle through the eye's plane is clipped at the near plane", "[pxpl5][view]") {
  // One corner behind: the edge towards it is cut 1 cm in front of the eye,
  // where it projects far to the right, so the box runs from x = 320 to the
  // screen edge along row 1 (y = 240).
  CHECK(regions({glm::dvec3(0, 0, -1), glm::dvec3(0.2, 0, -1), glm::dvec3(0, 0, 1)}) == std::vector<int>{7, 8, 9});
}

TEST_CASE("the binner follows the pose: turned left, the eye sees what lies to its left", "[pxpl5][view]") {
  const WorldTriangle left{glm::dvec3(-2, 0, 0), glm::dvec3(-2, 0, -0.5), glm::dvec3(-2, 0.5, 0)};
  CHECK(regions(left).empty());
  latsim::tracker::Pose turned;
  turned.orientation = glm::angleAxis(glm::radians(90.0), glm::dvec3(0, 1, 0));  // now looking down -x
  // Seen from there (X, Y, -d) = (-z, y, -2): x from 320 to 400, y from 160 to 240.
  CHECK(regions(left, turned) == std::vector<int>{7, 8});
  latsim::tracker::Pose moved;
  moved.position_m = glm::dvec3(0, 0, 5);  // stepped back: the triangle at z = -2 is 7 m away
  CHECK(regions({glm::dvec3(0, 0, -2), glm::dvec3(0.5, 0, -2), glm::dvec3(0, 0.5, -2)}, moved) == std::vector<int>{7});
}

TEST_CASE("binning deals the display list round-robin and counts what each processor sees", "[pxpl5][view]") {
  std::vector<WorldTriangle> list;
  for (int i = 0; i < 7; ++i) {
    const double z = i % 2 == 0 ? -2.0 : 2.0;  // even ones in front, odd ones behind
    list.push_back({glm::dvec3(0, 0, z), glm::dvec3(0.5, 0, z), glm::dvec3(0, 0.5, z)});
  }
  const ViewBinner binner(list, wide());
  const EyeWork w = binner.bin(latsim::tracker::Pose{}, 3);
  CHECK(w.on_screen_count == 4);
  CHECK(w.on_screen == std::vector<uint8_t>{1, 0, 1, 0, 1, 0, 1});
  // Processor p holds triangles p, p + 3, p + 6: 3, 2 and 2 of them.
  CHECK(w.bins.triangles(0) == 3);
  CHECK(w.bins.triangles(1) == 2);
  CHECK(w.bins.on_screen(0) == 2);  // triangles 0 and 6
  CHECK(w.bins.on_screen(1) == 1);  // triangle 4
  CHECK(w.bins.on_screen(2) == 1);  // triangle 2
  // Each visible one goes into regions 7 and 8.
  CHECK(w.bins.bin_entries(0) == 4);
  CHECK(w.bins.region_commands(7) == 4);
  CHECK(w.bins.region_commands(8) == 4);
  CHECK(w.bins.region_commands(0) == 0);
}

namespace {

std::vector<int> sphere_regions(const WorldSphere& s) {
  const ViewBinner binner({}, wide());
  std::vector<int> out;
  binner.regions_of(s, latsim::tracker::Pose{}, out);
  return out;
}

}  // namespace

// A sphere of radius r about (a, d) in one axis is seen between the slopes
// (a d -+ r sqrt(a^2 + d^2 - r^2)) / (d^2 - r^2) of the planes through the eye
// that touch it; on the 90 degree screen a slope s is drawn at x = (s + 1) 320
// and y = (1 - s / 0.75) 240.
TEST_CASE("a sphere covers the regions of the box its tangent planes cut out", "[pxpl5][view][spheres]") {
  // r = 0.2 at (0, 0, -2): slopes +-0.2 sqrt(3.96) / 3.96 = +-0.1005, x from
  // 287.8 to 352.2 (column 2), y from 207.8 to 272.2 (rows 1 and 2).
  CHECK(sphere_regions({glm::dvec3(0, 0, -2), 0.2}) == std::vector<int>{7, 12});
  // r = 0.5 at (-2.5, 0, -2): 0.35 m inside the left plane (|-2.5 + 2| / sqrt 2
  // < 0.5); x slopes (-5 -+ 0.5 sqrt 10) / 3.75 = -1.755 to -0.912, so x from
  // the left edge to 28.3 (column 0); y slopes +-0.5 sqrt 3.75 / 3.75 = +-0.258,
  // y from 157.4 to 322.6 (rows 1 and 2).
  CHECK(sphere_regions({glm::dvec3(-2.5, 0, -2), 0.5}) == std::vector<int>{5, 10});
}

TEST_CASE("spheres beyond one plane bin nowhere; one reaching the eye covers the screen", "[pxpl5][view][spheres]") {
  CHECK(sphere_regions({glm::dvec3(0, 0, 2), 0.2}).empty());      // behind the eye
  CHECK(sphere_regions({glm::dvec3(-5, 0, -2), 0.5}).empty());    // 2.1 m beyond the left plane
  CHECK(sphere_regions({glm::dvec3(0, 3, -2), 0.5}).empty());     // (3 - 1.5) / 1.25 = 1.2 m above the top plane
  CHECK(sphere_regions({glm::dvec3(0, 0, -0.1), 0.5}).size() == 20);  // reaches past the near plane
}

TEST_CASE("spheres follow the triangles in the display list and bin as their own kind", "[pxpl5][view][spheres]") {
  const std::vector<WorldTriangle> triangles{{glm::dvec3(0, 0, -2), glm::dvec3(0.5, 0, -2), glm::dvec3(0, 0.5, -2)}};
  const std::vector<WorldSphere> spheres{{glm::dvec3(0, 0, -2), 0.2}, {glm::dvec3(0, 0, 2), 0.2}};
  const EyeWork w = ViewBinner(triangles, wide(), spheres).bin(latsim::tracker::Pose{}, 3);
  // List positions 0 (triangle), 1 and 2 (spheres) on processors 0, 1 and 2.
  CHECK(w.on_screen_count == 1);
  CHECK(w.spheres_on_screen_count == 1);
  CHECK(w.bins.spheres(1) == 1);
  CHECK(w.bins.spheres_on_screen(1) == 1);
  CHECK(w.bins.spheres(2) == 1);
  CHECK(w.bins.spheres_on_screen(2) == 0);
  CHECK(w.bins.sphere_commands(1, 7) == 1);
  CHECK(w.bins.sphere_commands(1, 12) == 1);
  CHECK(w.bins.commands(0, 7) == 1);  // the triangle's
  CHECK(w.bins.sphere_commands(0, 7) == 0);
  CHECK(w.bins.region_commands(7) == 2);
  CHECK(w.bins.bin_entries(1) == 2);
}

TEST_CASE("culling back faces rejects a triangle whose corners turn clockwise as the eye sees them", "[pxpl5][view]") {
  ViewScreen culling = wide();
  culling.cull_back_faces = true;
  const ViewBinner binner({}, culling);
  std::vector<int> out;
  // Counter-clockwise seen from the eye (its normal +z points at the eye): kept.
  binner.regions_of(WorldTriangle{glm::dvec3(0, 0, -2), glm::dvec3(0.5, 0, -2), glm::dvec3(0, 0.5, -2)}, {}, out);
  CHECK(out == std::vector<int>{7, 8});
  // The same corners the other way round: its back is turned, rejected.
  binner.regions_of(WorldTriangle{glm::dvec3(0, 0, -2), glm::dvec3(0, 0.5, -2), glm::dvec3(0.5, 0, -2)}, {}, out);
  CHECK(out.empty());
  // Without culling both are binned.
  CHECK(regions({glm::dvec3(0, 0, -2), glm::dvec3(0, 0.5, -2), glm::dvec3(0.5, 0, -2)}) == std::vector<int>{7, 8});
}
