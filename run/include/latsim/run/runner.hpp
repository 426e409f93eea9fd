// Runs one scenario end to end and writes its self-describing results.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/des/time.hpp"
#include "latsim/results/ledger.hpp"
#include "latsim/results/timeline.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/scenario/schema.hpp"

namespace latsim::pipelines {
class PipelineRegistry;
}

namespace latsim::run {

/// The largest event estimate a run may have unless told otherwise
/// (RunOptions::max_events, --max-events): at the few million to tens of
/// millions of events per second the kernel runs, minutes of wall time.
inline constexpr double kDefaultMaxEvents = 2e9;

/// How far a running simulation got, for a progress display.
struct RunProgress {
  des::Time now;          ///< simulated time reached
  des::Time end;          ///< simulated time the run stops at
  uint64_t events = 0;    ///< events executed so far
};

/// A finished run's tables in memory, for a program that embeds latsim and
/// reads them without files: rows in the column order of the CSV files.
struct RunTables {
  std::vector<std::vector<int64_t>> frames;   ///< frames.csv rows (RunOptions::write_ledger)
  std::vector<std::vector<int64_t>> fields;   ///< fields.csv rows (write_ledger)
  std::vector<std::vector<int64_t>> tracker;  ///< tracker.csv rows (write_ledger)
  std::vector<results::SampleLog::Sample> samples;  ///< samples.csv rows (write_samples)
  /// The stage timeline when the run keeps it in memory: always when it
  /// writes no files; a run with out_dir streams it to timeline.csv instead.
  std::vector<results::Timeline::Entry> timeline;
  size_t timeline_dropped = 0;  ///< entries past /output/timeline_max_entries, counted only
};

/// How to run a scenario and what to write.
struct RunOptions {
  std::optional<uint64_t> seed;           ///< overrides /seed when set
  uint64_t replication = 0;               ///< independent random streams per replication
  std::filesystem::path out_dir;          ///< empty: write nothing, only return the summary
  /// Where the files wait until the run commits them to out_dir (empty:
  /// "<out_dir>.tmp.<pid>"); a sweep names one per run, which its claim guards.
  std::filesystem::path staging_dir;
  bool write_samples = false;             ///< samples.csv
  bool write_ledger = false;              ///< frames.csv, the per-frame ledger
  /// timeline.csv/.json where the scenario keeps a timeline (/output/timeline);
  /// false: none is recorded at all. The figures do not change.
  bool write_timeline = true;
  /// The PNG images captures write (frames/, ARP frames); false: they are still
  /// rendered and measured, and figures.json stays the same, but not written.
  bool write_images = true;
  /// figures.json and summary.json as one line of JSON rather than indented:
  /// less than half the bytes, for the thousands of runs of a sweep.
  bool compact_json = false;
  bool write_presentmon = true;           ///< presentmon.csv, the application's frames (pipelines that have them)
  bool profile = false;                   ///< wall time per event kind (two clock reads per event)
  std::vector<std::string> command_line;  ///< recorded in the summary
  /// When the command began (reading the scenario included); command_wall_s
  /// runs from here. Unset: from the start of run_scenario.
  std::optional<std::chrono::steady_clock::time_point> command_start;
  /// Set from outside (a signal): the simulation stops at the next event and
  /// run_scenario throws RunInterrupted, writing nothing.
  const std::atomic<bool>* stop = nullptr;
  /// Called every few thousand events while simulating.
  std::function<void(const RunProgress&)> progress;
  /// The largest number of events the run is expected to execute (its
  /// estimate, EventEstimate) before it is refused as bad input; 0: no limit.
  double max_events = kDefaultMaxEvents;
  /// The pipelines /pipeline/type may name; null: builtin_pipelines(). A
  /// program that embeds latsim runs its own pipelines through this.
  const pipelines::PipelineRegistry* pipelines = nullptr;
  /// When set, receives the run's tables once it has finished (RunTables).
  RunTables* tables = nullptr;
  /// When set and the run writes no files, receives the run's figures as the
  /// text a results-store record holds (results::FigureTree), built without
  /// their JSON tree, and the summary's "figures" is null; left empty where
  /// the figures need their JSON tree (the summary then holds them).
  std::string* figures_text = nullptr;
};

/// The simulation failed, not the input: which model's event, when, and why.
class RunFailure : public std::runtime_error {
 public:
  RunFailure(std::string model, des::Time at, const std::string& cause);
  const std::string& model() const { return model_; }
  des::Time at() const { return at_; }

 private:
  std::string model_;
  des::Time at_;
};

/// The run was stopped from outside (RunOptions::stop) before it finished.
class RunInterrupted : public std::runtime_error {
 public:
  RunInterrupted(des::Time at, des::Time end);
  /// Stopped after the simulation, `phase` ("while computing ...") naming where.
  RunInterrupted(const std::string& phase, des::Time end);
  des::Time at() const { return at_; }

 private:
  des::Time at_;
};

/// Builds the models a scenario asks for, runs it, and returns summary.json's
/// content; when out_dir is set, writes every result file atomically into a
/// staging directory renamed to out_dir at the end (RunFiles). Throws
/// scenario::ScenarioError on bad input, RunFailure when the simulation
/// fails, RunInterrupted when stopped and WriteError when a result cannot be
/// written; in every case nothing is left in out_dir.
nlohmann::json run_scenario(const scenario::ScenarioDocument& doc, const RunOptions& options);

/// Reads and builds everything without running (for `latsim validate`),
/// refusing a run whose event estimate is above max_events (0: no limit);
/// returns the warnings about legal but doubtful input.
std::vector<std::string> validate_scenario(const scenario::ScenarioDocument& doc, double max_events = kDefaultMaxEvents);

/// Validates as validate_scenario does and returns the run's event estimate
/// (the declared rates times the duration; docs/event-budget.md): events and
/// steps of work together.
double estimate_scenario_events(const scenario::ScenarioDocument& doc, double max_events = kDefaultMaxEvents);

/// The scenario as a run takes it, every default filled in (what a sweep
/// checks its axis pointers against): built once, without an event budget
/// (a sweep judges that with its own limit).
nlohmann::json resolve_defaults(const nlohmann::json& scenario, const std::filesystem::path& base_dir);

/// Every key a scenario may hold, from the parameter declarations of the
/// shared sections and of every registered pipeline. Built once per process:
/// it depends on nothing but the code.
const scenario::ObjectSchema& scenario_schema();

/// Loads a scenario file with overrides; an override may create an optional
/// section the scenario left out ("--set /output/timeline=false").
scenario::ScenarioDocument load_scenario(const std::filesystem::path& file, const std::vector<std::string>& overrides);
/// The same for a scenario given as JSON text, `name` standing for its file
/// in messages (ScenarioDocument::parse).
scenario::ScenarioDocument load_scenario_text(std::string_view text, const std::filesystem::path& name,
                                              const std::vector<std::string>& overrides);

/// latsim's version string and the git revision it was built from.
std::string latsim_version();
std::string latsim_git_revision();

}  // namespace latsim::run
