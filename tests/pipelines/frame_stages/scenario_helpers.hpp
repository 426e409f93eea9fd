// Runs shipped and in-code scenarios in-process through the runner.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

namespace latsim::testing {

/// The figures of a shipped scenario (path below scenarios/), with overrides.
inline nlohmann::json run_shipped(const std::string& file, std::vector<std::string> overrides = {}) {
  const auto doc = run::load_scenario(LATSIM_SOURCE_DIR "/scenarios/" + file, overrides);
  return run::run_scenario(doc, run::RunOptions{}).at("figures");
}

/// The figures of a scenario given as JSON (files relative to scenarios/modern).
inline nlohmann::json run_json(const nlohmann::json& scenario) {
  const auto doc = scenario::ScenarioDocument::from_json(scenario, LATSIM_SOURCE_DIR "/scenarios/modern");
  return run::run_scenario(doc, run::RunOptions{}).at("figures");
}

}  // namespace latsim::testing
