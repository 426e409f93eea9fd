// Every pipeline declares the figures its reader means first (summary.json
// "headline": the run line, tables and plots lead with them). This test is
// where those declarations are stated, one pipeline at a time, and it runs
// every shipped scenario to check each declared figure exists.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "latsim/run/builtin_pipelines.hpp"
#include "run_helpers.hpp"

using namespace latsim;
using Json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

// The headline a pipeline declares (before figures the run lacks are left
// out), and why a reader of that system reads it first.
std::vector<std::string> declared(const Json& scenario) {
  const Json& p = scenario.at("pipeline");
  const std::string type = p.at("type").get<std::string>();
  // Behind a time warp the warp's orientation is what is seen: the
  // application pose's motion-to-photon includes the frame the warp hides.
  if (type == "frame_stages" && p.contains("timewarp") && !p.at("timewarp").is_null())
    return {"rotation_latency_ms", "application_frame_rate_hz", "frames_missed", "warps_late", "smear_arcmin",
            "motion_to_photon_ms"};
  if (type == "frame_stages")
    return {"motion_to_photon_ms", "application_frame_rate_hz", "frames_missed", "smear_arcmin"};
  if (type == "double_buffer")
    return {"motion_to_photon_ms", "frame_rate_hz", "missed_refreshes", "registration_error_arcmin", "smear_arcmin"};
  // Address recalculation re-reads the orientation per line at scanout.
  if (type == "arp" || type == "priority" || type == "region_priority")
    return {"rotation_latency_ms", "translation_latency_ms", "registration_error_arcmin", "motion_to_photon_ms"};
  if (type == "frameless") return {"motion_to_photon_ms", "pixel_age_ms", "registration_error_arcmin"};
  if (type == "pxpl5_rc") return {"motion_to_photon_ms", "render_latency_fields", "frame_rate_hz", "missed_refreshes"};
  if (type == "pxpl5_slats") return {"motion_to_photon_ms", "render_latency_fields", "missed_fields", "missed_field_fraction"};
  // A replay's frames come at the capture's pace: what the present path made of them.
  if (type == "present_replay") return {"motion_to_photon_ms", "application_frame_rate_hz", "frames_dropped", "frame_rate_hz"};
  // A streamed headset: what the camera sees beside what the tool reports, the link, and the frames it costs.
  if (type == "streaming")
    return {"motion_to_photon_ms", "reported_total_ms", "rotation_latency_ms", "network_ms",
            "frames_late",         "frames_dropped",            "frames_reprojected"};
  return {};
}

std::vector<fs::path> shipped_scenarios() {
  std::vector<fs::path> found;
  for (const auto& e : fs::recursive_directory_iterator(LATSIM_SOURCE_DIR "/scenarios")) {
    const fs::path& p = e.path();
    if (p.extension() != ".json" || p.filename() == "base.json" || p.string().find("/sweeps/") != std::string::npos)
      continue;
    std::ifstream in(p);
    std::stringstream text;
    text << in.rdbuf();
    if (text.str().find("\"axes\":") != std::string::npos) continue;
    found.push_back(p);
  }
  std::sort(found.begin(), found.end());
  return found;
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
  for (const fs::path& file : shipped_scenarios()) {
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
