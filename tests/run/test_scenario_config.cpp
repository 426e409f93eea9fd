// Scenario reading: JSON pointers in every error, includes, overrides, defaults.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"
#include "run_helpers.hpp"

using latsim::scenario::ScenarioDocument;
using latsim::scenario::ScenarioError;
using Json = nlohmann::json;

namespace {

std::string error_pointer(const Json& scenario) {
  try {
    latsim::run::validate_scenario(ScenarioDocument::from_json(scenario, LATSIM_SOURCE_DIR "/scenarios"));
  } catch (const ScenarioError& e) {
    return e.pointer();
  }
  return "<no error>";
}

std::filesystem::path temp_dir() {
  auto d = std::filesystem::temp_directory_path() / "latsim_test_config";
  std::filesystem::create_directories(d);
  return d;
}

void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

}  // namespace

TEST_CASE("every bad-input class names its JSON pointer", "[scenario]") {
  using latsim::testing::base_scenario;
  Json s = base_scenario();
  s["tracker"]["rate_hz"] = -60;
  CHECK(error_pointer(s) == "/tracker/rate_hz");
  s = base_scenario();
  s["display"]["refresh_hz"] = 0;
  CHECK(error_pointer(s) == "/display/refresh_hz");
  s = base_scenario();
  s["display"]["width_px"] = "wide";
  CHECK(error_pointer(s) == "/display/width_px");
  s = base_scenario();
  s["display"]["widht_px"] = 640;
  CHECK(error_pointer(s) == "/display/widht_px");
  s = base_scenario();
  s["pipeline"]["render"]["fixed_ms"] = -1;
  CHECK(error_pointer(s) == "/pipeline/render/fixed_ms");
  s = base_scenario();
  s["pipeline"]["type"] = "no_such_pipeline";
  CHECK(error_pointer(s) == "/pipeline/type");
  s = base_scenario();
  s.erase("display");
  CHECK(error_pointer(s) == "/display");
  s = base_scenario();
  s["duration_s"] = 0;
  CHECK(error_pointer(s) == "/duration_s");
  s = base_scenario();
  s["extra"] = {{"a", 1}};
  CHECK(error_pointer(s) == "/extra");
  CHECK(error_pointer(base_scenario()) == "<no error>");
}

TEST_CASE("exact rational rates", "[scenario]") {
  Json s = {{"r", "60000/1001"}, {"d", 59.94}};
  const auto doc = ScenarioDocument::from_json(s, ".");
  const auto p = doc.root().rate_as_period("r", "60");
  CHECK(p.num == 1001);
  CHECK(p.den == 60000);
  const auto q = doc.root().rate_as_period("d", "60");
  CHECK(q.num == 50);  // 59.94 Hz = 2997/50 Hz exactly
  CHECK(q.den == 2997);
}

TEST_CASE("includes merge, overrides apply, retyped objects replace", "[scenario]") {
  const auto dir = temp_dir();
  write(dir / "base.json", R"({"a": {"x": 1, "y": 2}, "motion": {"type": "sinusoid", "yaw_amplitude_deg": 5}})");
  write(dir / "top.json", R"({"include": "base.json", "a": {"y": 3}, "motion": {"type": "still"}})");
  const auto doc = ScenarioDocument::load(dir / "top.json", {"/a/x=10", "/b=\"text\""});
  CHECK(doc.json()["a"]["x"] == 10);
  CHECK(doc.json()["a"]["y"] == 3);
  CHECK(doc.json()["b"] == "text");
  CHECK_FALSE(doc.json()["motion"].contains("yaw_amplitude_deg"));
  write(dir / "cycle.json", R"({"include": "cycle.json"})");
  CHECK_THROWS_AS(ScenarioDocument::load(dir / "cycle.json"), ScenarioError);
  CHECK_THROWS_AS(ScenarioDocument::load(dir / "top.json", {"/nope/deeper=1"}), ScenarioError);
}

TEST_CASE("malformed JSON reports the line", "[scenario]") {
  const auto dir = temp_dir();
  write(dir / "bad.json", "{\n  \"a\": 1,\n  \"b\": ,\n}\n");
  try {
    ScenarioDocument::load(dir / "bad.json");
    FAIL("no error");
  } catch (const ScenarioError& e) {
    CHECK(std::string(e.what()).find("line 3") != std::string::npos);
  }
}

TEST_CASE("the resolved scenario records every default applied", "[scenario]") {
  const auto doc = ScenarioDocument::from_json(latsim::testing::base_scenario(), LATSIM_SOURCE_DIR "/scenarios");
  latsim::run::validate_scenario(doc);
  CHECK(doc.resolved()["display"]["vblank_lines"] == 22);
  CHECK(doc.resolved()["display"]["scanout"] == "field");
  CHECK(doc.resolved()["pipeline"]["vsync"] == true);
}

TEST_CASE("a relative file name is relative to the file that names it, through includes", "[scenario]") {
  // top.json includes lib/base.json, which names its trace "data/head.csv":
  // the file is lib/data/head.csv, wherever the including file is. A name the
  // top file gives itself stays relative to the top file; an absolute name
  // is left alone.
  const auto dir = temp_dir() / "rebase";
  std::filesystem::create_directories(dir / "lib" / "data");
  write(dir / "lib" / "base.json", R"({"motion": {"type": "trace", "file": "data/head.csv"},
                                       "scene": {"type": "obj", "file": "/abs/room.obj"}})");
  write(dir / "top.json", R"({"include": "lib/base.json"})");
  write(dir / "own.json", R"({"include": "lib/base.json", "motion": {"file": "mine.csv"}})");
  write(dir / "nested.json", R"({"include": "top.json"})");
  const auto& schema = latsim::run::scenario_schema();
  CHECK(ScenarioDocument::load(dir / "top.json", {}, &schema).json()["motion"]["file"] == "lib/data/head.csv");
  CHECK(ScenarioDocument::load(dir / "nested.json", {}, &schema).json()["motion"]["file"] == "lib/data/head.csv");
  CHECK(ScenarioDocument::load(dir / "own.json", {}, &schema).json()["motion"]["file"] == "mine.csv");
  CHECK(ScenarioDocument::load(dir / "top.json", {}, &schema).json()["scene"]["file"] == "/abs/room.obj");
  // And the run reads the file from there: a missing one is named by its full path.
  const auto doc = latsim::run::load_scenario(dir / "top.json", {});
  CHECK(doc.root().child("motion").path("file") == (dir / "lib" / "data" / "head.csv").lexically_normal());
}
