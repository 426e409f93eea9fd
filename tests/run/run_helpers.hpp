// Builds small scenarios in code and runs them in-process.
#pragma once

#include <nlohmann/json.hpp>

#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

namespace latsim::testing {

/// A 60 Hz progressive mono HMD, tracker aligned with the refresh (both
/// phases fixed at zero, not drawn), instant rendering.
inline nlohmann::json base_scenario() {
  return {{"duration_s", 2},
          {"seed", 7},
          {"motion", {{"type", "constant"}, {"axis", {0, 1, 0}}, {"rate_deg_s", 30}}},
          {"tracker", {{"rate_hz", 60}, {"phase_ms", 0}}},
          {"display", {{"refresh_hz", 60}, {"width_px", 640}, {"height_px", 480}, {"hfov_deg", 60}, {"phase_ms", 0}}},
          {"pipeline", {{"type", "double_buffer"}, {"render", {{"fixed_ms", 0}}}}}};
}

inline nlohmann::json run(const nlohmann::json& scenario) {
  return run::run_scenario(scenario::ScenarioDocument::from_json(scenario, LATSIM_SOURCE_DIR "/scenarios"),
                                 run::RunOptions{});
}

inline const nlohmann::json& fig(const nlohmann::json& summary, const char* name) {
  return summary.at("figures").at(name);
}

}  // namespace latsim::testing
