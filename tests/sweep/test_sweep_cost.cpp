// Tests for the expected cost of a run: its one event estimate, from its one
// build, against the rates docs/event-budget.md states and the event counts
// BENCHMARKS.md measured for scanout at field, line and pixel level.
#include <catch2/catch.hpp>

#include "latsim/run/prepared_run.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/sweep/cost.hpp"

using latsim::sweep::longest_first;
using Json = nlohmann::json;

namespace {

/// The cost of a scenario with the sections of `s` (and a still head, a
/// tracker, a display and a double-buffered 2 ms render where `s` has none,
/// as every scenario must), built once as a run builds it.
double expected_cost(Json s) {
  if (!s.contains("motion")) s["motion"] = {{"type", "still"}};
  if (!s.contains("tracker")) s["tracker"] = Json::object();
  if (!s.contains("display")) s["display"] = Json::object();
  if (!s.contains("pipeline")) s["pipeline"] = {{"type", "double_buffer"}, {"render", {{"fixed_ms", 2}}}};
  const auto doc = latsim::scenario::ScenarioDocument::from_json(s, ".");
  return latsim::sweep::expected_cost(latsim::run::PreparedRun(doc, latsim::run::RunOptions{}).estimate());
}

Json hmd(const std::string& scanout) {
  return {{"duration_s", 10},
          {"display", {{"refresh_hz", 60}, {"width_px", 640}, {"height_px", 480}, {"scanout", scanout}}}};
}

// 10 s of a 60 Hz tracker, 60 Hz retraces and one 2 ms render per refresh
// (docs/event-budget.md): 600 events each.
constexpr double kBase = 3 * 600.0;

}  // namespace

TEST_CASE("expected cost grows with scanout events as measured", "[sweep][cost]") {
  // Line level adds one event per active line: 600 x 480 = 288,000. Pixel
  // level batches a line's pixels into one event (BENCHMARKS.md's fidelity
  // ladder counts 289,799 events for 10 s at line and pixel level alike);
  // pixel events add one per pixel_stride pixels: 600 x 480 x 640 / 8.
  CHECK(expected_cost(hmd("field")) == Approx(kBase));
  CHECK(expected_cost(hmd("line")) == Approx(kBase + 288000.0));
  CHECK(expected_cost(hmd("pixel")) == Approx(kBase + 288000.0));
  Json strided = hmd("pixel");
  strided["display"]["pixel_stride"] = 8;
  strided["display"]["pixel_events"] = true;
  CHECK(expected_cost(strided) == Approx(kBase + 184320000.0 / 8));
  CHECK(expected_cost(hmd("pixel")) < expected_cost(strided));
}

TEST_CASE("expected cost: interlace, stereo, exact rates and missing keys", "[sweep][cost]") {
  Json s = hmd("line");
  s["display"]["interlaced"] = true;  // a field scans half the lines
  CHECK(expected_cost(s) == Approx(kBase + 144000.0));
  s = hmd("field");
  s["host"] = {{"stereo", true}};  // one retrace and one render event serve both eyes
  CHECK(expected_cost(s) == Approx(kBase));
  s = hmd("field");
  s["display"]["refresh_hz"] = "60000/1001";
  CHECK(expected_cost(s) == Approx(600.0 + 2 * 10.0 * 60000.0 / 1001.0));
  // Keys left out take their declared defaults (docs/scenario-reference.md:
  // 10 s, a 60 Hz tracker and a 60 Hz 640 x 480 progressive display scanned
  // out per field; mono).
  CHECK(expected_cost(Json{{"duration_s", 3}}) == Approx(3.0 * 3 * 60.0));
  CHECK(expected_cost(Json::object()) == Approx(10.0 * 3 * 60.0));
  CHECK(expected_cost(Json{{"display", {{"scanout", "line"}}}}) == Approx(10.0 * 60.0 * (3 + 480.0)));
}

TEST_CASE("runs start longest first, ties in plan order", "[sweep][cost]") {
  const std::vector<double> cost{1.0, 3.0, 3.0, 2.0, 1.0};
  CHECK(longest_first({0, 1, 2, 3, 4}, cost) == std::vector<size_t>{1, 2, 3, 0, 4});
  CHECK(longest_first({4, 3, 0}, cost) == std::vector<size_t>{3, 4, 0});
  const std::vector<double> flat(6, 5.0);
  CHECK(longest_first({0, 1, 2, 3, 4, 5}, flat) == std::vector<size_t>{0, 1, 2, 3, 4, 5});
}
