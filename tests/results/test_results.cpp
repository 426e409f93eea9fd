// One path for results: named figures, one distribution format, warnings,
// and result files written atomically by the run.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "latsim/results/figures.hpp"
#include "latsim/results/run_files.hpp"
#include "run_helpers.hpp"

using namespace latsim;
using Json = nlohmann::json;

namespace {

std::string bytes_of(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::filesystem::path fresh(const std::string& name) {
  // The process id keeps test runs of several build directories apart.
  const auto dir =
      std::filesystem::temp_directory_path() / ("latsim_results_" + name + "." + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir;
}

}  // namespace

TEST_CASE("named figures nest by their dotted names; numeric parts are array elements", "[results]") {
  results::FigureTable t;
  t.set("utilisation.gp", 0.25);
  t.set("memories.1.renders", int64_t{7});
  t.set("memories.0.renders", int64_t{3});
  t.set("strategy", std::string("frameless"));
  t.set("complete", true);
  t.list("frames");
  t.object("stage_ms");
  // A figure has one value: a second one is a programming error, not an update.
  CHECK_THROWS_AS(t.set("strategy", std::string("double_buffer")), std::logic_error);
  const Json f = t.to_json({}, {{"fields", 12}});
  CHECK(f["utilisation"]["gp"] == 0.25);
  REQUIRE(f["memories"].is_array());
  CHECK(f["memories"][0]["renders"] == 3);
  CHECK(f["memories"][1]["renders"] == 7);
  CHECK(f["strategy"] == "frameless");
  CHECK(f["complete"] == true);
  CHECK(f["frames"] == Json::array());
  CHECK(f["stage_ms"] == Json::object());
  CHECK(f["counts"]["fields"] == 12);
}

TEST_CASE("every distribution has one format, whoever kept it", "[results]") {
  stats::Distribution own(0.005, false), kept(0.005, false);
  for (double v : {1.0, 2.0, 3.0, 4.0}) own.add(v);
  for (double v : {10.0, 30.0}) kept.add(v);
  results::FigureTable t;
  t.publish("stage_ms.SEND", kept);
  t.publish("transform_to_copy_end_fields", kept);
  CHECK_THROWS_AS(t.publish("stage_ms.SEND", own), std::logic_error);
  const Json f = t.to_json({{"render_latency_fields", own}, {"display_ms", own}}, {});
  for (const Json* d : {&f["display_ms"], &f["stage_ms"]["SEND"], &f["render_latency_fields"],
                        &f["transform_to_copy_end_fields"]}) {
    for (const char* key : {"count", "mean", "stddev", "min", "p50", "p90", "p99", "p999", "max", "histogram"})
      CHECK(d->contains(key));
  }
  CHECK(f["display_ms"]["mean"] == 2.5);                // (1 + 2 + 3 + 4) / 4
  CHECK(f["stage_ms"]["SEND"]["mean"] == 20.0);         // (10 + 30) / 2
  CHECK(f["render_latency_fields"]["count"] == 4);
  CHECK(f["transform_to_copy_end_fields"]["count"] == 2);
}

TEST_CASE("run files are written atomically into the run directory, or not at all", "[results]") {
  results::RunFiles none;
  CHECK_FALSE(none.enabled());
  none.write_text("x.txt", "nothing");
  CHECK(none.written().empty());
  const auto dir = fresh("files");
  const auto staging = results::staging_dir_of(dir, 4242);
  {
    results::RunFiles files(dir, staging);
    files.write_text("a.csv", "a,b\n1,2\n");
    files.write_text("sub/b.md", "# b\n");
    // Until the run commits, its files wait beside the run directory.
    CHECK_FALSE(std::filesystem::exists(dir));
    CHECK(bytes_of(staging / "a.csv") == "a,b\n1,2\n");
    files.write_text("summary.json", "{}\n");
    files.commit("summary.json");
    CHECK(files.written() == std::vector<std::string>{"a.csv", "sub/b.md", "summary.json"});
  }
  CHECK(bytes_of(dir / "a.csv") == "a,b\n1,2\n");
  CHECK(bytes_of(dir / "sub/b.md") == "# b\n");
  CHECK(bytes_of(dir / "summary.json") == "{}\n");
  CHECK_FALSE(std::filesystem::exists(staging));
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    CHECK(e.path().string().find(".tmp") == std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("a run that does not commit leaves no run directory and no staging directory", "[results]") {
  const auto dir = fresh("uncommitted");
  const auto staging = results::staging_dir_of(dir, 4243);
  {
    results::RunFiles files(dir, staging);
    files.write_text("timeline.csv", "t\n");
    CHECK(std::filesystem::exists(staging));
  }  // failed or interrupted: destroyed without commit
  CHECK_FALSE(std::filesystem::exists(dir));
  CHECK_FALSE(std::filesystem::exists(staging));
}

TEST_CASE("a write that fails names the file in the run directory and the system's reason", "[results]") {
  // The run directory's parent is a file: nothing can be made there (ENOTDIR).
  const auto blocker = fresh("unwritable");
  { std::ofstream(blocker) << "in the way"; }
  const auto dir = blocker / "run";
  results::RunFiles files(dir, results::staging_dir_of(dir, 4244));
  try {
    files.write_text("figures.json", "{}");
    FAIL("no error");
  } catch (const results::WriteError& e) {
    CHECK(std::string(e.what()).find("cannot write") != std::string::npos);
    CHECK(e.error_number() != 0);
  }
  std::filesystem::remove(blocker);
}

TEST_CASE("doubtful input is a warning in the summary, not an error", "[results]") {
  Json s = testing::base_scenario();
  s["transport"] = {{"type", "direct"}, {"poll_interval_ms", 10}};
  const Json summary = testing::run(s);
  REQUIRE(summary["warnings"].size() == 1);
  CHECK(summary["warnings"][0] == "/transport/poll_interval_ms: ignored: read only when type=serial, host=poll");
  CHECK(testing::run(testing::base_scenario())["warnings"] == Json::array());
}

TEST_CASE("the resolved scenario records host, output and transport defaults", "[results]") {
  const Json summary = testing::run(testing::base_scenario());
  const Json& r = summary["scenario"];
  CHECK(r["host"]["stereo"] == false);
  CHECK(r["host"]["ipd_m"] == 0.064);
  CHECK(r["output"]["timeline"] == true);
  CHECK(r["output"]["timeline_max_entries"] == 200000);
  CHECK(r["transport"]["type"] == "direct");
}

TEST_CASE("a pipeline's image files go through the run and figures.json stays byte-identical", "[results]") {
  const auto a = fresh("arp_a"), b = fresh("arp_b");
  for (const auto& dir : {a, b}) {
    run::RunOptions options;
    options.out_dir = dir;
    run::run_scenario(run::load_scenario(LATSIM_SOURCE_DIR "/scenarios/arp/arp_basic.json",
                                                     {"/duration_s=0.6", "/pipeline/frame_times_s=[0.5]",
                                                      "/pipeline/face_px=32"}),
                            options);
  }
  CHECK(std::filesystem::exists(a / "arp_frame_500ms.png"));
  CHECK(bytes_of(a / "arp_frame_500ms.png") == bytes_of(b / "arp_frame_500ms.png"));
  CHECK(bytes_of(a / "figures.json") == bytes_of(b / "figures.json"));
  std::filesystem::remove_all(a);
  std::filesystem::remove_all(b);
}
