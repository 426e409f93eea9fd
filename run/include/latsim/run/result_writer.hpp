// Collects a finished run's figures and writes its self-describing results:
// figures.json (what the scenario and seed determine), the ledger, the
// sample log and the timeline, and summary.json last.
#pragma once

#include <chrono>

#include <nlohmann/json.hpp>

#include "latsim/run/builder.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

namespace latsim::run {

/// What the run knows at its end about its shared models.
results::RunTotals totals_of(const Run& run);

/// Lets the pipeline and the recorders finish and returns every figure; warns
/// about legal input whose run says little or nothing.
nlohmann::json figures_of(Run& run);

/// summary.json's content for a run whose simulation took `wall_s`; when the
/// run writes files, writes every result file and commits the run directory
/// (summary.json last).
nlohmann::json write_results(Run& run, const scenario::ScenarioDocument& doc, const RunOptions& options,
                             nlohmann::json figures, double wall_s,
                             std::chrono::steady_clock::time_point command_start);

}  // namespace latsim::run
