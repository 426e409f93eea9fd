// Runs whose costs come from captures: the latency a hand derivation gives,
// the stage durations equal to the capture's values, the end of a capture
// that must stop, bootstrap replications, and the shipped scenarios.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/display/raster_timing.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"
#include "temp_file.hpp"

using latsim::capture::test::TempFile;
using Json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

// Two processes; game.exe's MsGPUBusy is 5, 25 (and 5 again for the stop case).
const std::string kTwoFrames =
    "Application,ProcessID,MsBetweenPresents,MsGPUBusy\n"
    "game.exe,40,16.6,5\n"
    "other.exe,41,16.6,99\n"
    "game.exe,40,16.6,25\n";

/// A 60 Hz progressive mono HMD and a 60 Hz tracker, both phases zero, a
/// double-buffered renderer whose cost is `trace`.
Json double_buffer(const Json& trace) {
  return {{"duration_s", 2},
          {"seed", 7},
          {"motion", {{"type", "constant"}, {"axis", {0, 1, 0}}, {"rate_deg_s", 30}}},
          {"tracker", {{"rate_hz", 60}, {"phase_ms", 0}}},
          {"display", {{"refresh_hz", 60}, {"width_px", 640}, {"height_px", 480}, {"hfov_deg", 60}, {"phase_ms", 0}}},
          {"pipeline", {{"type", "double_buffer"}, {"render", {{"trace", trace}}}}}};
}

Json run(const Json& scenario, latsim::run::RunOptions options = {}) {
  return latsim::run::run_scenario(latsim::scenario::ScenarioDocument::from_json(scenario, LATSIM_SOURCE_DIR "/scenarios"),
                                   options);
}

const Json& fig(const Json& summary, const char* name) { return summary.at("figures").at(name); }

latsim::display::RasterTiming timing_60hz() {
  latsim::display::RasterParams p;
  p.field_period = latsim::des::RationalSeconds{1, 60};
  return latsim::display::RasterTiming(p);
}

}  // namespace

TEST_CASE("in-order replay through double buffering gives the latency derived by hand") {
  const TempFile csv("two_frames.csv", kTwoFrames);
  const Json out = run(double_buffer({{"file", csv.path().string()}, {"column", "MsGPUBusy"}, {"application", "game.exe"}}));
  // F = 16.667 ms. The renderer takes the sample of retrace 0 and draws for
  // 5 ms; the image waits for retrace 1. The renderer resumes at retrace 1
  // with that retrace's sample and draws for 25 ms, ending at 41.7 ms: too
  // late for retrace 2, so field 2 shows the first image again and field 3
  // the second. At retrace 3 (50 ms) the 5 ms frame starts again: a cycle
  // of 3 fields whose images are 1, 2 and 2 fields old at their retrace.
  // So image_age_ms (per field, at its first line) is F + l for a third of
  // the fields and 2F + l for the others, l being the first line's delay.
  const auto t = timing_60hz();
  const double field_ms = t.field_period_ms();
  const double first_line_ms = (t.line_time(1, 0) - t.field_start(1)).to_ms();
  const Json& age = fig(out, "image_age_ms");
  CHECK(age["min"].get<double>() == Approx(field_ms + first_line_ms).margin(1e-6));
  CHECK(age["max"].get<double>() == Approx(2 * field_ms + first_line_ms).margin(1e-6));
  // Fields 1 to 119 (or 120) of the 2 s: a partial cycle moves the mean by at most F / count.
  const double count = age["count"].get<double>();
  CHECK(count >= 119);
  CHECK(age["mean"].get<double>() == Approx(5.0 / 3.0 * field_ms + first_line_ms).margin(field_ms / count));
  // 40 cycles of 50 ms, two frames each: the last begins at 1966.7 ms (retrace 118) and
  // the renderer's next wait ends at retrace 120, t = 2 s, which a 2 s run does not reach.
  const Json& c = out.at("captures").at(0);
  CHECK(c["pointer"] == "/pipeline/render/trace");
  CHECK(c["generation"] == "current");
  CHECK(c["rows_read"] == 3);
  CHECK(c["rows_of_other_processes"] == 1);
  CHECK(c["values"] == 2);
  CHECK(c["values_played"] == 80);
  CHECK(c["wraps"] == 39);
  CHECK(count == 119);  // fields 1 to 119
  CHECK(c["mean_ms"].get<double>() == Approx(15.0));
}

TEST_CASE("a stage's durations in the timeline are the capture's values, in order") {
  const TempFile csv("stage_costs.csv", "frame,gpu_ms\n1,3\n2,7.25\n3,NA\n4,11\n5,2\n");
  const std::vector<double> expected{3, 7.25, 11, 2};  // the NA row skipped
  Json s = double_buffer({});
  s["pipeline"] = {{"type", "frame_stages"},
                   {"processors", {{{"name", "cpu"}}, {{"name", "gpu"}}}},
                   {"stages",
                    {{{"name", "I"}, {"on", "cpu"}, {"start", "retrace"}, {"samples_pose", true}, {"cost", {{"fixed_ms", 0.5}}}},
                     {{"name", "G"}, {"on", "gpu"}, {"cost", {{"trace", {{"file", csv.path().string()}, {"column", "gpu_ms"}}}}}}}}};
  s["duration_s"] = 0.5;
  const fs::path dir = fs::temp_directory_path() / ("latsim-capture-run-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  latsim::run::RunOptions options;
  options.out_dir = dir;
  run(s, options);
  std::ifstream in(dir / "timeline.csv");
  std::string line;
  std::getline(in, line);  // stage,frame,eye,unit,start_ms,end_ms
  std::vector<double> durations;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::vector<std::string> f;
    for (std::string cell; std::getline(row, cell, ',');) f.push_back(cell);
    if (f.at(0) == "G") durations.push_back(std::stod(f.at(5)) - std::stod(f.at(4)));
  }
  fs::remove_all(dir);
  REQUIRE(durations.size() >= 20);  // a frame a field for 0.5 s, less the last ones
  for (size_t i = 0; i < durations.size(); ++i) CHECK(durations[i] == Approx(expected[i % 4]).margin(1e-6));
}

TEST_CASE("at_end stop: the run ends when the capture does, with a warning") {
  const TempFile csv("three_frames.csv", kTwoFrames + "game.exe,40,16.6,5\n");
  const Json out = run(double_buffer(
      {{"file", csv.path().string()}, {"column", "MsGPUBusy"}, {"process_id", 40}, {"at_end", "stop"}}));
  // Frames of 5 (0 to 5 ms), 25 (16.7 to 41.7 ms) and 5 ms (50 to 55 ms);
  // the renderer wants a fourth value at retrace 4, t = 66.67 ms.
  const Json& w = out.at("warnings");
  REQUIRE(w.size() >= 1);
  CHECK(w.dump().find("ran out after its 3 values at simulated t = 0.0666667 s") != std::string::npos);
  CHECK(out.at("captures").at(0)["exhausted"] == true);
  CHECK(out.at("captures").at(0)["values_played"] == 3);
  CHECK(fig(out, "image_age_ms")["count"].get<int64_t>() <= 4);
}

TEST_CASE("bootstrap: replications differ, the same replication repeats") {
  std::string text = "ms\n";
  for (int i = 0; i < 60; ++i) text += std::to_string(2 + (i * 7) % 23) + "\n";
  const TempFile csv("bootstrap.csv", text);
  const Json s = double_buffer({{"file", csv.path().string()}, {"column", "ms"}, {"order", "bootstrap"}, {"block_length", 6}});
  latsim::run::RunOptions second;
  second.replication = 1;
  const Json a = run(s), b = run(s, second), a2 = run(s);
  CHECK(a.at("fingerprint") != b.at("fingerprint"));
  CHECK(fig(a, "image_age_ms")["mean"] != fig(b, "image_age_ms")["mean"]);
  CHECK(a.at("fingerprint") == a2.at("fingerprint"));
}

TEST_CASE("the shipped measured scenarios run on each generation") {
  for (const char* name : {"current_cpu_gpu", "v1_double_buffer_stop", "v2_bootstrap"}) {
    INFO(name);
    const auto doc = latsim::run::load_scenario(std::string(LATSIM_SOURCE_DIR) + "/scenarios/measured/" + name + ".json",
                                                {"/duration_s=1"});
    const Json out = latsim::run::run_scenario(doc, {});
    REQUIRE(out.contains("captures"));
    for (const Json& c : out.at("captures")) {
      CHECK(c["process_id"] == 1268);
      CHECK(c["values_played"].get<int64_t>() > 20);
    }
    CHECK(fig(out, "motion_to_photon_ms")["count"].get<int64_t>() > 0);
  }
}
