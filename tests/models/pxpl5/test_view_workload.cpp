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
