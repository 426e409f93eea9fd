// Time warp of frames: exact identity, the undefined edge of a rotation, the
// shift of a translated plane and the gap a translation uncovers, each
// against positions derived from the pinhole geometry.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "latsim/renderer/image_warp.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using latsim::renderer::Camera;
using latsim::tracker::Pose;
using latsim::renderer::Frame;
using latsim::renderer::inside_rotated_source;
using latsim::renderer::warp_with_depth;

namespace {

constexpr int kW = 160, kH = 120;
const glm::vec3 kUndefined(1.0f, 0.0f, 1.0f);

// Red encodes the source column, green the row, so a warped pixel says where it came from.
glm::vec3 code(int x, int y) { return glm::vec3(static_cast<float>(x) / kW, static_cast<float>(y) / kH, 0.25f); }

int column_of(const glm::vec3& c) { return static_cast<int>(std::lround(c.x * kW)); }

/// A frame from the identity pose where pixel x sees a surface at depth_of(x) metres along -z.
template <class DepthOf>
Frame planes(const Camera& cam, DepthOf depth_of) {
  Frame f = Frame::cleared(kW, kH, glm::vec3(0.0f));
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      f.colour.at(x, y) = code(x, y);
      const double axis_depth = depth_of(x);
      // The ray caster stores the distance along the unit ray.
      f.depth.at(x, y) = static_cast<float>(axis_depth / -cam.head_direction(x + 0.5, y + 0.5).z);
    }
  return f;
}

Frame sky(const Camera& cam) { return planes(cam, [](int) { return std::numeric_limits<double>::infinity(); }); }

glm::dquat yaw(double deg) { return glm::angleAxis(units::deg_to_rad(deg), glm::dvec3(0, 1, 0)); }

}  // namespace

TEST_CASE("image warp: warping to the source pose gives the source back exactly") {
  const Camera cam(90.0, kW, kH);
  const Frame src = planes(cam, [](int x) { return x < kW / 2 ? 1.0 : 3.0; });
  const latsim::tracker::Pose pose{glm::dvec3(0.1, 1.6, -0.2), yaw(20.0)};
  const auto out = warp_with_depth(src, cam, pose, pose, kUndefined);
  CHECK(out.undefined_px == 0);
  int mismatches = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) mismatches += out.frame.colour.at(x, y) != src.colour.at(x, y) ? 1 : 0;
  CHECK(mismatches == 0);
}

TEST_CASE("image warp: a rotation-only warp leaves the edge the head turns towards undefined") {
  const Camera cam(90.0, kW, kH);
  const double theta = 10.0;  // a yaw to the left: new pixels appear at the left edge
  const latsim::tracker::Pose from{glm::dvec3(0.0), yaw(0.0)}, to{glm::dvec3(0.0), yaw(theta)};
  const auto out = warp_with_depth(sky(cam), cam, from, to, kUndefined);
  const int y = kH / 2;
  for (int x = 0; x < kW; ++x) {
    // Turning left by theta puts the old forward theta to the right of the new one, so a ray phi
    // right of the new forward is phi - theta right of the old one and lands at source column
    // w/2 + f tan(phi - theta).
    const double phi = std::atan((x + 0.5 - 0.5 * kW) / cam.focal_px());
    const double src_x = 0.5 * kW + cam.focal_px() * std::tan(phi - units::deg_to_rad(theta));
    CHECK(inside_rotated_source(cam, from.orientation, to.orientation, x, y) == (src_x >= 0.0 && src_x < kW));
    const bool defined = out.defined[static_cast<size_t>(y * kW + x)] != 0;
    if (src_x < 0.0) {
      CHECK_FALSE(defined);
    } else if (src_x > 1.0 && src_x < kW - 1.0) {
      // Inside the hull of the source pixel centres: defined, showing the nearest source column
      // (nearest along the quad grid, which bends tan() into straight pieces: a few hundredths off).
      REQUIRE(defined);
      CHECK(std::abs(column_of(out.frame.colour.at(x, y)) + 0.5 - src_x) <= 0.55);
    }
  }
  // Half a field of view of 45 deg: tan(45 - 10) = 0.700 of the half width is left: 0.150 of the
  // width, 24 columns, are undefined at the left edge.
  int undefined = 0;
  for (int x = 0; x < kW; ++x) undefined += out.defined[static_cast<size_t>(y * kW + x)] ? 0 : 1;
  const double expected = 0.5 * kW * (1.0 - std::tan(units::deg_to_rad(45.0 - theta)));
  CHECK(std::abs(undefined - expected) <= 1.0);
}

TEST_CASE("image warp: a translated fronto-parallel plane shifts by focal x offset / depth") {
  const Camera cam(90.0, kW, kH);
  const double depth = 2.0;
  const double shift_px = 8.0;
  const double dx = shift_px * depth / cam.focal_px();  // eye moves right: the plane moves left
  const Frame src = planes(cam, [&](int) { return depth; });
  const auto out = warp_with_depth(src, cam, latsim::tracker::Pose{}, latsim::tracker::Pose{glm::dvec3(dx, 0, 0), glm::dquat(1, 0, 0, 0)},
                                   kUndefined);
  const int y = kH / 2;
  for (int x = 1; x + 10 < kW; ++x) {
    REQUIRE(out.defined[static_cast<size_t>(y * kW + x)] != 0);
    CHECK(column_of(out.frame.colour.at(x, y)) == x + 8);
  }
  // The right edge: the last 8 columns have nothing behind them.
  int undefined = 0;
  for (int x = 0; x < kW; ++x) undefined += out.defined[static_cast<size_t>(y * kW + x)] ? 0 : 1;
  CHECK(std::abs(undefined - 8) <= 1);
}

TEST_CASE("image warp: a translation uncovers a gap behind a near surface as wide as the parallax difference") {
  const Camera cam(90.0, kW, kH);
  const double near_m = 1.0, far_m = 4.0;
  const double dx = 16.0 * near_m / cam.focal_px();  // near plane moves 16 px left, the far one 4 px
  const Frame src = planes(cam, [&](int x) { return x < kW / 2 ? near_m : far_m; });
  const auto out = warp_with_depth(src, cam, latsim::tracker::Pose{}, latsim::tracker::Pose{glm::dvec3(dx, 0, 0), glm::dquat(1, 0, 0, 0)},
                                   kUndefined);
  const int y = kH / 2;
  // The near half ends at column 80 - 16 = 64, the far half starts at 80 - 4 = 76: 12 columns of gap.
  int gap = 0;
  for (int x = 40; x < 120; ++x) gap += out.defined[static_cast<size_t>(y * kW + x)] ? 0 : 1;
  CHECK(std::abs(gap - 12) <= 1);
  CHECK(out.frame.colour.at(70, y) == kUndefined);
  CHECK(column_of(out.frame.colour.at(60, y)) == 76);
  CHECK(column_of(out.frame.colour.at(90, y)) == 94);
}
