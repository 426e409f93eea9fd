// Frame capture: pinned images, thread-count independence, and nothing cast
// unless a scenario asks for frames.
#include <catch2/catch.hpp>

#include <cstdio>

#include "frames_helpers.hpp"
#include "latsim/scenario/config.hpp"

namespace des = latsim::des;
namespace pipelines = latsim::pipelines;
namespace scenario = latsim::scenario;
using namespace latsim::frames_test;

namespace {

std::string hex(uint64_t v) {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace

TEST_CASE("a still head's captured field is pinned by hash and equals the truth", "[frames]") {
  nlohmann::json s = small_scenario();
  capture(s, {{"at_s", {0.1}}, {"threads", 1}});
  const auto dir = fresh_dir("golden");
  const auto summary = run(s, dir);
  const auto& frames = fig(summary, "frames");
  REQUIRE(frames.size() == 1);
  CHECK(frames[0]["field"] == 6);
  CHECK(frames[0]["image_error"].get<double>() == 0.0);
  CHECK(frames[0]["files"].size() == 4);
  for (const char* what : {"displayed", "truth", "diff", "age"})
    CHECK(std::filesystem::exists(dir / "frames" / (std::string("0000_") + what + ".png")));
  // Pinned: a change here means the capture (or the renderer) draws differently.
  CHECK(hex(file_hash(dir / "frames/0000_displayed.png")) == "b68748df9b03e0e5");
  CHECK(file_hash(dir / "frames/0000_displayed.png") == file_hash(dir / "frames/0000_truth.png"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("an interlaced capture of a turning head is pinned by hash", "[frames]") {
  nlohmann::json s = small_scenario();
  s["display"]["interlaced"] = true;
  s["motion"] = {{"type", "constant"}, {"axis", {0, 1, 0}}, {"rate_deg_s", 60}};
  s["pipeline"]["render"] = {{"fixed_ms", 20}};
  capture(s, {{"at_s", {0.3}}, {"threads", 1}});
  const auto dir = fresh_dir("interlaced");
  const auto summary = run(s, dir);
  const auto& frames = fig(summary, "frames");
  REQUIRE(frames.size() == 1);
  // A turning head and a frame behind: the displayed image is not the truth.
  CHECK(frames[0]["image_error"].get<double>() > 0.0);
  CHECK(hex(file_hash(dir / "frames/0000_displayed.png")) == "c2f252363e716a06");
  std::filesystem::remove_all(dir);
}

TEST_CASE("captures do not depend on the number of threads", "[frames]") {
  for (const char* strategy : {"frameless", "double_buffer"}) {
    nlohmann::json s = small_scenario();
    s["motion"] = {{"type", "constant"}, {"axis", {0, 1, 0}}, {"rate_deg_s", 45}};
    s["pipeline"] = frameless(strategy);
    capture(s, {{"every_nth_refresh", 10}, {"max_captures", 3}, {"threads", 1}});
    const auto one = fresh_dir(std::string("threads1_") + strategy);
    const auto a = run(s, one);
    s["frames"]["threads"] = 3;
    const auto three = fresh_dir(std::string("threads3_") + strategy);
    const auto b = run(s, three);
    REQUIRE(fig(a, "frames").size() == 3);
    CHECK(fig(a, "frames") == fig(b, "frames"));
    for (const auto& entry : fig(a, "frames"))
      for (const auto& file : entry["files"]) {
        const std::string name = file.get<std::string>();
        INFO(strategy << " " << name);
        CHECK(file_bytes(one / name) == file_bytes(three / name));
      }
    std::filesystem::remove_all(one);
    std::filesystem::remove_all(three);
  }
}

TEST_CASE("without a frames section nothing is loaded, cast or written", "[frames]") {
  nlohmann::json s = small_scenario();
  s.erase("scene");
  const auto dir = fresh_dir("none");
  const auto summary = run(s, dir);
  CHECK_FALSE(summary.at("figures").contains("frames"));
  CHECK_FALSE(std::filesystem::exists(dir / "frames"));
  CHECK(std::filesystem::exists(dir / "summary.json"));
  std::filesystem::remove_all(dir);

  // A mesh the scene names is read with the scenario (frames or not), so
  // that a bad one is the scenario's error, found by validate too; it is
  // cast only when a captured field is.
  s["scene"] = {{"type", "obj"}, {"file", "objects/pyramid.obj"}};
  SECTION("disabled frames cast and write nothing") {
    s["frames"] = {{"enabled", false}, {"at_s", {0.1}}};
    const auto off = run(s, dir);
    CHECK_FALSE(off.at("figures").contains("frames"));
    CHECK_FALSE(std::filesystem::exists(dir / "frames"));
  }
  SECTION("frames due after the run's end capture nothing") {
    s["frames"] = {{"at_s", {5.0}}};
    const auto late = run(s);
    CHECK(late.at("figures").at("frames").empty());
  }
  SECTION("a mesh that does not exist is an error at /scene/file, with frames or without") {
    s["scene"]["file"] = "no/such/scene.obj";
    for (const bool enabled : {false, true}) {
      s["frames"] = {{"enabled", enabled}, {"at_s", {0.1}}};
      try {
        run(s);
        FAIL("a missing mesh was accepted");
      } catch (const scenario::ScenarioError& e) {
        CHECK(e.pointer() == "/scene/file");
      }
    }
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("bad frames settings name the key", "[frames]") {
  nlohmann::json s = small_scenario();
  capture(s, {{"threads", 2}});
  try {
    run(s);
    FAIL("a frames section without captures was accepted");
  } catch (const scenario::ScenarioError& e) {
    CHECK(e.pointer() == "/frames/at_s");
  }
  capture(s, {{"at_s", {0.1}}, {"eye", 1}});
  CHECK_THROWS_AS(run(s), scenario::ScenarioError);
  capture(s, {{"at_s", {0.1}}, {"background", {1, 1}}});
  CHECK_THROWS_AS(run(s), scenario::ScenarioError);
}
