// Captures of time-warped images: the undefined edge of a rotation-only warp
// measured against the pinhole geometry, and a warp with depth that changes
// nothing when the head does not move.
#include <catch2/catch.hpp>

#include <cmath>

#include "scenario_helpers.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using latsim::testing::run_json;
using Json = nlohmann::json;

namespace {


/// The reference time warp (application read at V_k, warp read at
/// V_{k+2} - 2) at 62.5 Hz on a 320 x 240, 90 degree display, with captures.
Json warped_capture(const char* mode, double rate_deg_s) {
  Json stage = [](const char* name, const char* on, double ms) {
    return Json{{"name", name}, {"on", on}, {"cost", {{"fixed_ms", ms}}}};
  }("S", "cpu1", 9);
  return {
      {"duration_s", 0.3},
      {"motion", {{"type", "constant"}, {"axis", {0, 1, 0}}, {"rate_deg_s", rate_deg_s}, {"position_m", {0, 1.6, 0}}}},
      {"tracker", {{"rate_hz", 1000}}},
      {"display", {{"refresh_hz", 62.5}, {"width_px", 320}, {"height_px", 240}, {"vblank_lines", 0},
                   {"hblank_px", 0}, {"hfov_deg", 90}}},
      {"scene", {{"type", "room"}}},
      {"frames", {{"at_s", {0.2}}}},
      {"pipeline",
       {{"type", "frame_stages"},
        {"processors", {{{"name", "cpu1"}}, {{"name", "cpu2"}}, {{"name", "gpu"}}}},
        {"stages",
         {{{"name", "I"}, {"on", "cpu1"}, {"samples_pose", true}, {"cost", {{"fixed_ms", 1}}}},
          stage,
          {{"name", "R"}, {"on", "cpu2"}, {"start", "retrace"}, {"cost", {{"fixed_ms", 10}}}},
          {{"name", "G"}, {"on", "gpu"}, {"start", "stream"}, {"lag_ms", 1}, {"cost", {{"fixed_ms", 10}}}}}},
        {"timewarp",
         {{"mode", mode},
          {"stages", {{{"name", "W"}, {"on", "gpu"}, {"samples_pose", true}, {"cost", {{"fixed_ms", 2}}}}}}}}}}};
}

}  // namespace

TEST_CASE("warped frames: a rotation-only warp leaves undefined what the head turned into view") {
  // The image is rendered from the pose read at V_k and warped to the pose
  // read at V_{k+2} - 2: 30 ms of a 60 deg/s yaw, 1.8 deg to the left. In
  // angles: pixel (x, y) looks at azimuth a = atan((x + 0.5 - 160) / f) right
  // of the new forward and elevation e with tan e = (120 - y - 0.5) / f x
  // cos a; a yaw keeps e and puts the ray at azimuth a - 1.8 deg from the old
  // forward, where the source image has it at column 160 + f tan(a - 1.8)
  // and row 120 - f tan e / cos(a - 1.8). Outside the source image the warp
  // has nothing: a band of 10 columns at the left edge, and, since a ray
  // further off-axis lands further from the horizon, wedges at its top and
  // bottom corners.
  const Json f = run_json(warped_capture("rotation", 60.0));
  REQUIRE(f.at("frames").size() == 1);
  const double focal = 160.0 / std::tan(units::deg_to_rad(45.0));
  const double theta = units::deg_to_rad(1.8);
  int64_t undefined = 0, band = 0;
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) {
      const double a = std::atan((x + 0.5 - 160.0) / focal);
      const double tan_e = (120.0 - y - 0.5) / focal * std::cos(a);
      const double px = 160.0 + focal * std::tan(a - theta);
      const double py = 120.0 - focal * tan_e / std::cos(a - theta);
      const bool outside = px < 0.0 || px >= 320.0 || py < 0.0 || py >= 240.0;
      undefined += outside ? 1 : 0;
      band += (y == 120 && outside) ? 1 : 0;
    }
  CHECK(band == 10);
  CHECK(undefined > 240 * 10);
  CHECK(f.at("frames").at(0).at("undefined_px").get<int64_t>() == undefined);
}

TEST_CASE("warped frames: with a still head a warp with depth shows exactly the truth") {
  const Json f = run_json(warped_capture("positional", 0.0));
  REQUIRE(f.at("frames").size() == 1);
  CHECK(f.at("frames").at(0).at("undefined_px").get<int64_t>() == 0);
  CHECK(f.at("frames").at(0).at("image_error").get<double>() == 0.0);
}
