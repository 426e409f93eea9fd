// Tests for the expected cost of a run: its one event estimate, from its one
// build, against the rates docs/event-budget.md states and the event counts
// BENCHMARKS.md measured for scanout at field, line and pixel level.
#include <catch2/catch.hpp>

#include <utility>
#include <vector>

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

namespace {

using latsim::sweep::point_chunks;

// The chunks as [begin, end) pairs.
std::vector<std::pair<size_t, size_t>> ranges(const std::vector<size_t>& points, unsigned threads) {
  std::vector<std::pair<size_t, size_t>> out;
  for (const auto& c : point_chunks(points, threads)) out.emplace_back(c.begin, c.end);
  return out;
}

// `runs` replications of each of `points` points, replications innermost (a plan's order).
std::vector<size_t> plan_order(size_t points, size_t runs) {
  std::vector<size_t> order;
  for (size_t p = 0; p < points; ++p) order.insert(order.end(), runs, p);
  return order;
}

}  // namespace

TEST_CASE("a thread takes a point's replications together, in pieces that leave every thread work", "[sweep][cost]") {
  // 200 points x 10 on 16 threads: pieces up to 2000 / 64 = 31 runs, so each
  // point is one piece of 10 runs.
  const auto shape = point_chunks(plan_order(200, 10), 16);
  REQUIRE(shape.size() == 200);
  for (size_t p = 0; p < 200; ++p) {
    CHECK(shape[p].begin == 10 * p);
    CHECK(shape[p].end == 10 * p + 10);
  }
  // One point of 100 replications on 2 threads: pieces up to 100 / 8 = 12
  // runs, eight of 12 and one of the last 4.
  const auto one_point = ranges(plan_order(1, 100), 2);
  REQUIRE(one_point.size() == 9);
  for (size_t k = 0; k < 8; ++k) CHECK(one_point[k] == std::make_pair(12 * k, 12 * k + 12));
  CHECK(one_point[8] == std::make_pair(size_t{96}, size_t{100}));
  // On 16 threads 100 / 64 is 1: every run alone, as many pieces as runs.
  CHECK(point_chunks(plan_order(1, 100), 16).size() == 100);
  // Pieces end where the point changes: 3 runs of point 0 and 5 of point 1
  // on one thread, pieces up to 8 / 4 = 2 runs.
  using R = std::vector<std::pair<size_t, size_t>>;
  CHECK(ranges({0, 0, 0, 1, 1, 1, 1, 1}, 1) == R{{0, 2}, {2, 3}, {3, 5}, {5, 7}, {7, 8}});
  // A point met again later (resumed runs, costs in another order) starts a new piece.
  CHECK(ranges({4, 4, 7, 4, 4, 4, 4, 4}, 1) == R{{0, 2}, {2, 3}, {3, 5}, {5, 7}, {7, 8}});
  CHECK(point_chunks({}, 4).empty());
}
