// Collects a finished run's figures and writes its self-describing results:
// figures.json (what the scenario and seed determine), the ledger, the
// sample log and the timeline, and summary.json last.
#pragma once

#include <chrono>
#include <optional>

#include <nlohmann/json.hpp>

#include "latsim/run/builder.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

namespace latsim::run {

/// What the run knows at its end about its shared models.
results::RunTotals totals_of(const Run& run);

/// A run's figures: their JSON tree, or (asked for as text) the FigureTree
/// that writes them, its JSON null.
struct RunFigures {
  nlohmann::json json;
  std::optional<results::FigureTree> tree;
};

/// Lets the pipeline and the recorders finish and returns every figure, as
/// a FigureTree when `as_text` and the tree can hold them; warns about legal
/// input whose run says little or nothing.
RunFigures figures_of(Run& run, bool as_text = false);

/// summary.json's content for a run whose simulation took `wall_s`; when the
/// run writes files, writes every result file and commits the run directory
/// (summary.json last).
nlohmann::json write_results(Run& run, const RunOptions& options, RunFigures figures, double wall_s,
                             std::chrono::steady_clock::time_point command_start);

}  // namespace latsim::run
