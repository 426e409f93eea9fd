// Tests for sweep files: expansion (cartesian, zip, ranges), run ids, and
// errors that name the sweep file and the JSON pointer.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "latsim/scenario/choice_list.hpp"
#include "latsim/sweep/plan.hpp"

using latsim::sweep::expand_points;
using latsim::sweep::expand_range;
using latsim::sweep::run_id_of;
using latsim::sweep::SweepError;
using latsim::sweep::SweepPlan;
using Json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

/// A scratch directory holding a small base scenario, removed at scope exit.
struct Scratch {
  fs::path dir;
  Scratch() {
    dir = fs::temp_directory_path() / ("latsim_sweep_plan_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "base.json") << R"({"duration_s": 1, "seed": 7,
      "display": {"refresh_hz": 60, "interlaced": false},
      "transport": {"type": "serial", "poll_interval_ms": 0}})";
  }
  ~Scratch() { fs::remove_all(dir); }
  fs::path sweep_file() const { return dir / "sweep.json"; }
};

// Stands in for the scenario reader: fills /tracker/rate_hz as a default.
Json fake_resolve(const Json& scenario, const fs::path&) {
  Json resolved = scenario;
  resolved["tracker"]["rate_hz"] = 60;
  return resolved;
}

SweepPlan plan_of(const Scratch& s, const Json& sweep) { return SweepPlan::from_json(sweep, s.sweep_file(), fake_resolve); }

// The SweepError message of a sweep that must be rejected.
std::string error_of(const Scratch& s, const Json& sweep) {
  try {
    (void)plan_of(s, sweep);
  } catch (const SweepError& e) {
    return e.what();
  }
  FAIL("the sweep was accepted");
  return {};
}

}  // namespace

TEST_CASE("cartesian sweeps vary the last axis fastest, replications innermost", "[sweep]") {
  Scratch s;
  const Json sweep = {{"base", "base.json"},
                      {"replications", 2},
                      {"axes", {{{"pointer", "/display/refresh_hz"}, {"values", {60, "60000/1001"}}},
                                {{"pointer", "/transport/poll_interval_ms"}, {"range", {{"from", 0}, {"to", 30}, {"step", 10}}}}}}};
  const SweepPlan plan = plan_of(s, sweep);
  REQUIRE(plan.point_count() == 8);
  REQUIRE(plan.runs().size() == 16);
  const auto& r = plan.runs();
  CHECK(plan.scenario(r[0])["display"]["refresh_hz"] == 60);
  CHECK(plan.scenario(r[0])["transport"]["poll_interval_ms"] == 0);
  CHECK(r[0].replication == 0);
  CHECK(r[1].replication == 1);
  CHECK(r[1].point == 0);
  CHECK(plan.scenario(r[2])["transport"]["poll_interval_ms"] == 10);
  CHECK(plan.scenario(r[15])["display"]["refresh_hz"] == "60000/1001");
  CHECK(plan.scenario(r[15])["transport"]["poll_interval_ms"] == 30);
  // The replications of a point share its scenario; each has its own id.
  CHECK(&plan.scenario(r[0]) == &plan.scenario(r[1]));
  CHECK(plan.points().size() == 8);
  // The base scenario's seed is kept when the sweep names none.
  CHECK(r[0].seed == 7);
  std::set<std::string> ids;
  for (const auto& run : r) ids.insert(run.run_id);
  CHECK(ids.size() == r.size());
  CHECK(plan.describe(r[3]) == "/display/refresh_hz=60, /transport/poll_interval_ms=10");
}

TEST_CASE("zip sweeps pair the i-th values and need equal lengths", "[sweep]") {
  Scratch s;
  Json sweep = {{"base", "base.json"},
                {"mode", "zip"},
                {"axes", {{{"pointer", "/display/refresh_hz"}, {"values", {60, 72, 90}}},
                          {{"pointer", "/transport/poll_interval_ms"}, {"values", {1, 2, 3}}}}}};
  const SweepPlan plan = plan_of(s, sweep);
  REQUIRE(plan.runs().size() == 3);
  CHECK(plan.scenario(plan.runs()[2])["display"]["refresh_hz"] == 90);
  CHECK(plan.scenario(plan.runs()[2])["transport"]["poll_interval_ms"] == 3);
  sweep["axes"][1]["values"] = {1, 2};
  CHECK_THAT(error_of(s, sweep), Catch::Contains("sweep.json: /axes/1: zip mode needs axes of equal length"));
}

TEST_CASE("ranges include both ends, keep integers integral, and reject bad steps", "[sweep]") {
  const fs::path f = "s.json";
  auto ints = expand_range({{"from", 0}, {"to", 30}, {"step", 10}}, f, "/r");
  REQUIRE(ints.size() == 4);
  CHECK(ints[3].is_number_integer());
  CHECK(ints[3] == 30);
  auto reals = expand_range({{"from", 0.5}, {"to", 1.5}, {"step", 0.1}}, f, "/r");
  REQUIRE(reals.size() == 11);
  CHECK(reals[10].get<double>() == Approx(1.5));
  auto down = expand_range({{"from", 3}, {"to", 0}, {"step", -1}}, f, "/r");
  REQUIRE(down.size() == 4);
  CHECK(down[3] == 0);
  CHECK_THROWS_WITH(expand_range({{"from", 0}, {"to", 3}, {"step", 0}}, f, "/r"), Catch::Contains("/r/step"));
  CHECK_THROWS_WITH(expand_range({{"from", 0}, {"to", 3}, {"step", -1}}, f, "/r"), Catch::Contains("never reaches"));
  CHECK_THROWS_WITH(expand_range({{"from", 0}, {"step", 1}}, f, "/r"), Catch::Contains("/r/to"));
}

TEST_CASE("expand_points enumerates like an odometer", "[sweep]") {
  const auto cart = expand_points({2, 3}, false);
  REQUIRE(cart.size() == 6);
  CHECK(cart[1] == std::vector<size_t>{0, 1});
  CHECK(cart[3] == std::vector<size_t>{1, 0});
  const auto zip = expand_points({3, 3}, true);
  REQUIRE(zip.size() == 3);
  CHECK(zip[2] == std::vector<size_t>{2, 2});
}

TEST_CASE("an axis label names the axis in plan.json; a bad one is refused at its pointer", "[sweep]") {
  Scratch s;
  const Json axis = {{"pointer", "/display/refresh_hz"}, {"values", {60, 90}}, {"label", "refresh"}};
  const auto plan = plan_of(s, {{"base", "base.json"}, {"axes", {axis}}});
  CHECK(plan.to_json()["axes"][0]["label"] == "refresh");
  Json bad = axis;
  bad["label"] = "";
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {bad}}}), Catch::Contains("/axes/0/label:"));
  bad["label"] = 3;
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {bad}}}), Catch::Contains("/axes/0/label:"));
}

TEST_CASE("a sweep file chooses the report's columns by their results.csv names", "[sweep]") {
  Scratch s;
  const Json axis = {{"pointer", "/display/refresh_hz"}, {"values", {60, 90}}};
  const auto plan = plan_of(s, {{"base", "base.json"}, {"axes", {axis}},
                                {"figures", {"rotation_latency_mean_ms", "missed_refreshes"}}});
  CHECK(plan.figures() == std::vector<std::string>{"rotation_latency_mean_ms", "missed_refreshes"});
  CHECK(plan.to_json()["figures"][1] == "missed_refreshes");
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {axis}}, {"figures", {"mtp_mean_ms", "latency"}}}),
             Catch::Contains("/figures/1: unknown value \"latency\"; expected one of"));
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {axis}}, {"figures", Json::array()}}),
             Catch::Contains("/figures: expected a non-empty array"));
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {axis}}, {"figures", {"wall_s"}}}),
             Catch::Contains("/figures/0:"));
}

TEST_CASE("a sweep file chooses any figure a run reports by its path; a refused one lists whole names", "[sweep]") {
  Scratch s;
  const Json axis = {{"pointer", "/display/refresh_hz"}, {"values", {60, 90}}};
  // The application's counts and rates, a nested count and a distribution's statistic.
  const std::vector<std::string> chosen{"frames_missed", "application_frame_rate_hz", "counts.fields",
                                        "display_ms.p99", "frames_rewarped", "memories.0.renders"};
  // memories.<n>.renders holds an index: it cannot be listed, so it is refused.
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {axis}}, {"figures", chosen}}),
             Catch::Contains("/figures/5: unknown value \"memories.0.renders\""));
  const std::vector<std::string> listed(chosen.begin(), chosen.end() - 1);
  CHECK(plan_of(s, {{"base", "base.json"}, {"axes", {axis}}, {"figures", listed}}).figures() == listed);
  // The choices (hundreds of names) are cut before the first whole name past
  // 200 characters: the list ends with a closing quote, then "… and N more".
  const std::string error = error_of(s, {{"base", "base.json"}, {"axes", {axis}}, {"figures", {"latency"}}});
  const size_t list = error.find("expected one of ");
  const size_t more = error.find(", \u2026 and ");
  REQUIRE(list != std::string::npos);
  REQUIRE(more != std::string::npos);
  CHECK(error[more - 1] == '"');
  CHECK(more - (list + 16) <= latsim::scenario::kChoiceListChars);
  CHECK_THAT(error, Catch::EndsWith(" more"));
  CHECK(error.find("(") == std::string::npos);  // not cut by the message's length limit ("... (N bytes)")
}

TEST_CASE("a sweep without axes is the base scenario's replications", "[sweep]") {
  // One point with no axis value; replications 0 .. 3 of the same seed.
  CHECK(expand_points({}, false) == std::vector<std::vector<size_t>>{{}});
  CHECK(expand_points({}, true) == std::vector<std::vector<size_t>>{{}});
  Scratch s;
  for (const char* mode : {"cartesian", "zip"}) {
    const auto plan = plan_of(s, {{"base", "base.json"}, {"axes", Json::array()}, {"replications", 4}, {"mode", mode}});
    REQUIRE(plan.runs().size() == 4);
    for (size_t r = 0; r < 4; ++r) {
      CHECK(plan.runs()[r].point == 0);
      CHECK(plan.runs()[r].replication == r);
      CHECK(plan.scenario(plan.runs()[r]) == plan.scenario(plan.runs()[0]));
    }
  }
}

TEST_CASE("an axis pointer missing from the base scenario is reported with its pointer", "[sweep]") {
  Scratch s;
  Json sweep = {{"base", "base.json"},
                {"axes", {{{"pointer", "/display/refresh_hz"}, {"values", {60}}},
                          {{"pointer", "/display/no_such_key"}, {"values", {1, 2}}}}}};
  const std::string message = error_of(s, sweep);
  CHECK_THAT(message, Catch::Contains("sweep.json: /axes/1/pointer:"));
  CHECK_THAT(message, Catch::Contains("/display/no_such_key"));
  // A key the reader fills with a default is a fine axis.
  sweep["axes"][1]["pointer"] = "/tracker/rate_hz";
  CHECK(plan_of(s, sweep).runs().size() == 2);
}

TEST_CASE("sweep file errors name the JSON pointer", "[sweep]") {
  Scratch s;
  const Json axis = {{"pointer", "/display/refresh_hz"}, {"values", {60}}};
  CHECK_THAT(error_of(s, {{"base", "missing.json"}, {"axes", {axis}}}), Catch::Contains("missing.json: cannot read the scenario file: No such file"));
  CHECK_THAT(error_of(s, {{"base", "missing.json"}, {"axes", {axis}}}), Catch::Contains("sweep.json: /base: "));
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", "none"}}), Catch::Contains("/axes: expected an array"));
  CHECK_THAT(error_of(s, {{"base", "base.json"}}), Catch::Contains("/axes: expected an array"));
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {axis}}, {"mode", "diagonal"}}), Catch::Contains("/mode:"));
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {axis}}, {"replications", 0}}), Catch::Contains("/replications:"));
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {axis}}, {"colour", 1}}), Catch::Contains("/colour: unknown key"));
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {{{"pointer", "display"}, {"values", {1}}}}}}),
             Catch::Contains("/axes/0/pointer: \"display\" is not a JSON pointer"));
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {{{"pointer", "/duration_s"}, {"values", {1, 2, 1}}}}}}),
             Catch::Contains("/axes/0/values/2: value 1 appears twice"));
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {axis, axis}}}), Catch::Contains("/axes/1/pointer: "));
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {axis}}, {"overrides", {{"/nowhere/x", 1}}}}),
             Catch::Contains("/overrides/~1nowhere~1x: "));
}

TEST_CASE("in zip mode a value may repeat on an axis, but two points may not be the same scenario", "[sweep]") {
  Scratch s;
  const Json labels = {{"pointer", "/duration_s"}, {"values", {1, 2, 3}}};
  const Json rates = {{"pointer", "/display/refresh_hz"}, {"values", {60, 60, 90}}};
  Json sweep = {{"base", "base.json"}, {"axes", {labels, rates}}, {"mode", "zip"}};
  const auto plan = plan_of(s, sweep);
  CHECK(plan.point_count() == 3);
  sweep["axes"] = {{{"pointer", "/duration_s"}, {"values", {1, 1}}}, {{"pointer", "/display/refresh_hz"}, {"values", {60, 60}}}};
  CHECK_THAT(error_of(s, sweep), Catch::Contains("run the same scenario"));
}

TEST_CASE("overrides and the sweep seed apply to every run and change its id", "[sweep]") {
  Scratch s;
  Json sweep = {{"base", "base.json"}, {"axes", {{{"pointer", "/display/refresh_hz"}, {"values", {60}}}}}};
  const std::string plain_id = plan_of(s, sweep).runs()[0].run_id;
  CHECK(plan_of(s, sweep).runs()[0].run_id == plain_id);  // deterministic
  sweep["seed"] = 99;
  sweep["overrides"] = {{"/duration_s", 0.25}};
  const SweepPlan plan = plan_of(s, sweep);
  CHECK(plan.runs()[0].seed == 99);
  CHECK(plan.scenario(plan.runs()[0])["seed"] == 99);
  CHECK(plan.scenario(plan.runs()[0])["duration_s"] == 0.25);
  CHECK(plan.runs()[0].run_id != plain_id);
}

TEST_CASE("run ids hash the serialised scenario, seed and replication once per scenario", "[sweep]") {
  // FNV-1a over the whole text, then the splitmix64 finaliser, written out here as plain arithmetic.
  const Json scenario = {{"display", {{"refresh_hz", 90}}}, {"duration_s", 0.5}};
  const std::string text = scenario.dump() + "\nseed=7\nreplication=3";
  uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : text) h = (h ^ c) * 0x100000001b3ULL;
  h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
  h = (h ^ (h >> 27)) * 0x94d049bb133111ebULL;
  h ^= h >> 31;
  char want[17];
  std::snprintf(want, sizeof want, "%016llx", static_cast<unsigned long long>(h));
  CHECK(latsim::sweep::RunIds(scenario).of(7, 3) == want);
  CHECK(run_id_of(scenario, 7, 3) == want);
}

TEST_CASE("sweep file errors read as scenario errors: type, range, unknown key", "[sweep]") {
  Scratch s;
  const Json axis = {{"pointer", "/display/refresh_hz"}, {"values", {60}}};
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {axis}}, {"replications", 0}}),
             Catch::Contains("sweep.json: /replications: must lie in [1, 1000000], got 0"));
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {axis}}, {"replications", "two"}}),
             Catch::Contains("sweep.json: /replications: expected an integer"));
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {axis}}, {"mode", "diagonal"}}),
             Catch::Contains("sweep.json: /mode: unknown value \"diagonal\"; expected one of \"cartesian\", \"zip\""));
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {{{"pointer", "/duration_s"}, {"values", {1}}, {"valuez", 1}}}}}),
             Catch::Contains("sweep.json: /axes/0/valuez: unknown key"));
  CHECK_THAT(error_of(s, {{"axes", {axis}}}), Catch::Contains("sweep.json: /base: required key is missing"));
  CHECK_THAT(error_of(s, {{"base", "base.json"}, {"axes", {axis}}, {"seed", -1}}),
             Catch::Contains("sweep.json: /seed: expected an integer from 0 to 18446744073709551615"));
}

TEST_CASE("run ids are 16 hex digits that differ widely between replications", "[sweep]") {
  const Json scenario = {{"duration_s", 1}};
  const std::string a = run_id_of(scenario, 1, 0), b = run_id_of(scenario, 1, 1);
  REQUIRE(a.size() == 16);
  CHECK(a.find_first_not_of("0123456789abcdef") == std::string::npos);
  CHECK(a == run_id_of(Json{{"duration_s", 1}}, 1, 0));
  CHECK(a != run_id_of(scenario, 2, 0));
  int differing = 0;
  for (size_t i = 0; i < a.size(); ++i) differing += a[i] != b[i];
  CHECK(differing >= 8);
}

TEST_CASE("plan.json lists every run with its values", "[sweep]") {
  Scratch s;
  const Json sweep = {{"base", "base.json"}, {"replications", 3}, {"axes", {{{"pointer", "/display/interlaced"}, {"values", {true, false}}}}}};
  const Json j = plan_of(s, sweep).to_json();
  REQUIRE(j["runs"].size() == 6);
  CHECK(j["runs"][5]["values"][0] == false);
  CHECK(j["runs"][5]["replication"] == 2);
  CHECK(j["points"] == 2);
}
