// Runs one scenario end to end and writes its self-describing results.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/pipelines/run_files.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/scenario/schema.hpp"

namespace latsim::pipelines {

/// How to run a scenario and what to write.
struct RunOptions {
  std::optional<uint64_t> seed;           ///< overrides /seed when set
  uint64_t replication = 0;               ///< independent random streams per replication
  std::filesystem::path out_dir;          ///< empty: write nothing, only return the summary
  bool write_samples = false;             ///< samples.csv
  bool write_ledger = false;              ///< frames.csv, the per-frame ledger
  std::vector<std::string> command_line;  ///< recorded in the summary
  /// When the command began (reading the scenario included); command_wall_s
  /// runs from here. Unset: from the start of run_scenario.
  std::optional<std::chrono::steady_clock::time_point> command_start;
};

/// Builds the models a scenario asks for, runs it, and returns summary.json's
/// content; when out_dir is set, writes every result file atomically
/// (temporary file, then rename). Throws scenario::ScenarioError on bad input
/// before anything is written.
nlohmann::json run_scenario(const scenario::ScenarioDocument& doc, const RunOptions& options);

/// Reads and builds everything without running (for `latsim validate`);
/// returns the warnings about legal but doubtful input.
std::vector<std::string> validate_scenario(const scenario::ScenarioDocument& doc);

/// Every key a scenario may hold, from the parameter declarations of the
/// shared sections and of every registered pipeline. Built once per process:
/// it depends on nothing but the code.
const scenario::ObjectSchema& scenario_schema();

/// Loads a scenario file with overrides; an override may create an optional
/// section the scenario left out ("--set /output/timeline=false").
scenario::ScenarioDocument load_scenario(const std::filesystem::path& file, const std::vector<std::string>& overrides);

/// latsim's version string and the git revision it was built from.
std::string latsim_version();
std::string latsim_git_revision();

}  // namespace latsim::pipelines
