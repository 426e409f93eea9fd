// Every pipeline names the headline its reader means first (summary.json
// "headline": the run line, tables and plots lead with it); the figure
// registry ranks each headline's figures. This test states which headline
// each pipeline uses, and why, and runs every shipped scenario to check the
// run's headline is the registry's, less the figures the run lacks.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "latsim/results/figure_registry.hpp"
#include "latsim/run/builtin_pipelines.hpp"
#include "run_helpers.hpp"

using namespace latsim;
using Json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

// The headline set a pipeline uses, and why a reader of that system reads it first.
std::string headline_set(const Json& scenario) {
  const Json& p = scenario.at("pipeline");
  const std::string type = p.at("type").get<std::string>();
  // Behind a time warp the warp's orientation is what is seen: the
  // application pose's motion-to-photon includes the frame the warp hides.
  if (type == "frame_stages" && p.contains("timewarp") && !p.at("timewarp").is_null()) return "time_warp";
  if (type == "frame_stages") return "frame_stages";
  if (type == "double_buffer") return "double_buffer";
  // Address recalculation re-reads the orientation per line at scanout.
  if (type == "arp" || type == "priority" || type == "region_priority") return "address_recalculation";
  if (type == "frameless") return "frameless";
  if (type == "pxpl5_rc") return "pxpl5_rc";
  if (type == "pxpl5_slats") return "pxpl5_slats";
  // A replay's frames come at the capture's pace: what the present path made of them.
  if (type == "present_replay") return "present_replay";
  // A streamed headset: what the camera sees beside what the tool reports, the link, and the frames it costs.
  if (type == "streaming") return "streaming";
  // A see-through headset: how late the real world is seen, where the time goes, and the frames it costs.
  if (type == "passthrough") return "passthrough";
  return {};
}

// The headline a pipeline declares (before figures the run lacks are left out).
std::vector<std::string> declared(const Json& scenario) {
  const std::string set = headline_set(scenario);
  if (set.empty()) return {};
  return results::FigureRegistry::builtin().headline(set);
}

}  // namespace

TEST_CASE("every registered pipeline has a declared headline here", "[headline]") {
  for (const std::string& name : run::builtin_pipelines().names()) {
    INFO(name);
    CHECK_FALSE(declared(Json{{"pipeline", {{"type", name}}}}).empty());
  }
}

TEST_CASE("every shipped scenario leads with its pipeline's headline figures", "[headline]") {
  int warped = 0;
  for (const fs::path& file : testing::shipped_scenarios()) {
    INFO(file.string());
    const Json summary =
        run::run_scenario(run::load_scenario(file.string(), {"/duration_s=0.5"}), run::RunOptions{});
    const Json& scenario = summary.at("scenario");
    const std::vector<std::string> expected = declared(scenario);
    REQUIRE_FALSE(expected.empty());
    const auto headline = summary.at("headline").get<std::vector<std::string>>();
    REQUIRE_FALSE(headline.empty());
    // The headline is the declared list in its order, less figures the run lacks.
    std::vector<std::string> kept;
    for (const std::string& name : expected)
      if (summary.at("figures").contains(name)) kept.push_back(name);
    // A distribution with no sample is left out as well.
    kept.erase(std::remove_if(kept.begin(), kept.end(),
                              [&](const std::string& n) {
                                const Json& f = summary.at("figures").at(n);
                                return f.is_object() && f.contains("count") && f.at("count").get<int64_t>() == 0;
                              }),
               kept.end());
    CHECK(headline == kept);
    const Json& p = scenario.at("pipeline");
    if (p.at("type") == "frame_stages" && p.contains("timewarp") && !p.at("timewarp").is_null()) {
      ++warped;
      CHECK(headline.front() == "rotation_latency_ms");
    }
  }
  CHECK(warped >= 3);  // timewarp, continuous_timewarp, timewarp_overload, ...
}
