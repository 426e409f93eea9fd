// Tests for the expected cost of a run, against the event counts that
// BENCHMARKS.md measured for scanout at field, line and pixel level.
#include <catch2/catch.hpp>

#include "latsim/scenario/config.hpp"
#include "latsim/sweep/cost.hpp"

using latsim::sweep::longest_first;
using Json = nlohmann::json;

namespace {

/// The cost of a scenario with the sections of `s` (and a head motion, a
/// tracker and a display where `s` has none, as every scenario must), read
/// as a run reads them.
double expected_cost(Json s) {
  if (!s.contains("motion")) s["motion"] = {{"type", "still"}};
  if (!s.contains("tracker")) s["tracker"] = Json::object();
  if (!s.contains("display")) s["display"] = Json::object();
  return latsim::sweep::expected_cost(latsim::scenario::ScenarioDocument::from_json(s, "."));
}

Json hmd(const std::string& scanout) {
  return {{"duration_s", 10},
          {"display", {{"refresh_hz", 60}, {"width_px", 640}, {"height_px", 480}, {"scanout", scanout}}}};
}

}  // namespace

TEST_CASE("expected cost grows with scanout events as measured", "[sweep][cost]") {
  // 10 s at 60 Hz: 600 fields; line level adds 600 x 480 = 288,000 events and
  // pixel level 600 x 480 x 640 = 184,320,000 (BENCHMARKS.md, fidelity table).
  CHECK(expected_cost(hmd("field")) == Approx(600.0));
  CHECK(expected_cost(hmd("line")) == Approx(288000.0));
  CHECK(expected_cost(hmd("pixel")) == Approx(184320000.0));
  Json strided = hmd("pixel");
  strided["display"]["pixel_stride"] = 8;
  CHECK(expected_cost(strided) == Approx(184320000.0 / 8));
}

TEST_CASE("expected cost: interlace, stereo, exact rates and missing keys", "[sweep][cost]") {
  Json s = hmd("line");
  s["display"]["interlaced"] = true;  // a field scans half the lines
  CHECK(expected_cost(s) == Approx(144000.0));
  s = hmd("field");
  s["host"] = {{"stereo", true}};
  CHECK(expected_cost(s) == Approx(1200.0));
  s = hmd("field");
  s["display"]["refresh_hz"] = "60000/1001";
  CHECK(expected_cost(s) == Approx(10.0 * 60000.0 / 1001.0));
  // Keys left out take their declared defaults (docs/scenario-reference.md:
  // 10 s, a 60 Hz 640 x 480 progressive display scanned out per field;
  // mono).
  CHECK(expected_cost(Json{{"duration_s", 3}}) == Approx(3.0 * 60.0));
  CHECK(expected_cost(Json::object()) == Approx(10.0 * 60.0));
  CHECK(expected_cost(Json{{"display", {{"scanout", "line"}}}}) == Approx(10.0 * 60.0 * 480.0));
}

TEST_CASE("runs start longest first, ties in plan order", "[sweep][cost]") {
  const std::vector<double> cost{1.0, 3.0, 3.0, 2.0, 1.0};
  CHECK(longest_first({0, 1, 2, 3, 4}, cost) == std::vector<size_t>{1, 2, 3, 0, 4});
  CHECK(longest_first({4, 3, 0}, cost) == std::vector<size_t>{3, 4, 0});
  const std::vector<double> flat(6, 5.0);
  CHECK(longest_first({0, 1, 2, 3, 4, 5}, flat) == std::vector<size_t>{0, 1, 2, 3, 4, 5});
}
