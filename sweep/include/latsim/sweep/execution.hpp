// Running one run of a sweep inside a shared sweep directory: claim it, make
// sure nobody finished it meanwhile, clear what an interrupted attempt left,
// run it, give the claim back. Every backend (threads, shards, MPI ranks)
// runs runs through this one path.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/run/bound_scenario.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/sweep/claims.hpp"
#include "latsim/sweep/journal.hpp"
#include "latsim/sweep/keep.hpp"
#include "latsim/sweep/plan.hpp"
#include "latsim/sweep/segment.hpp"
#include "latsim/sweep/store.hpp"

namespace latsim::sweep {

/// Everything needed to run one run, without the plan (MPI ranks receive this).
struct RunTask {
  size_t index = 0;  ///< position in plan order
  std::string run_id;
  uint64_t seed = 0;
  uint64_t replication = 0;
  /// The point's scenario, shared by its replications (in a plan: the plan's own).
  std::shared_ptr<const nlohmann::json> scenario;
  std::filesystem::path base_dir;
  /// Also write the traces (timeline, images, ledger, samples); false: figures only.
  bool keep_traces = false;

  static RunTask of(const SweepPlan& plan, const SweepRun& run, const KeepPolicy& keep);
  nlohmann::json to_json() const;
  static RunTask from_json(const nlohmann::json& j);
};

/// How one attempt ended, and where its time went.
struct RunAttempt {
  /// stopped: a stop signal ended the run midway (nothing of it kept);
  /// not_started: the sweep was stopping before this run began.
  enum class Result { ran, failed, finished_already, busy, stopped, not_started } result = Result::failed;
  std::string message;     ///< failed: what went wrong; busy: who holds the run
  /// failed because the sweep directory cannot be written (full, read-only):
  /// the runs after it would fail the same way.
  bool storage_unusable = false;
  double resolve_s = 0.0;  ///< reading and binding the scenario (once a point on each thread)
  double run_s = 0.0;      ///< run_scenario: building the models, simulating, the figures (and a kept run's files)
  double simulate_s = 0.0; ///< of which simulating (the run's own wall_s)
  double record_s = 0.0;   ///< writing the run's record into the results store, and its mark
  double claim_s = 0.0;    ///< claiming, journal, clearing temporaries, releasing

  nlohmann::json to_json() const;
  static RunAttempt from_json(const nlohmann::json& j);
};

/// What every run of this process records and writes besides its results.
struct RunSettings {
  bool write_samples = false;  ///< samples.csv, for the runs that keep their traces
  bool write_ledger = false;   ///< frames.csv, for the runs that keep their traces
  bool write_presentmon = false;  ///< presentmon.csv, for the runs that keep their traces
  std::vector<std::string> command_line;  ///< recorded in each summary: the same for every backend
  const std::atomic<bool>* stop = nullptr;  ///< set by a stop signal: runs end at their next event
  double max_events = run::kDefaultMaxEvents;  ///< a run's largest event estimate (run::RunOptions::max_events)
};

/// Runs runs in one sweep directory on behalf of one process, on up to
/// `workers` threads at once, each with its own segment of the results store
/// (so that threads share nothing while they record). A stale claim taken
/// over is reported on stderr as a warning at once.
class RunExecutor {
 public:
  RunExecutor(const SweepStore& store, RunClaims& claims, const SweepJournal& journal, RunSettings settings,
              unsigned workers);
  ~RunExecutor();
  RunExecutor(const RunExecutor&) = delete;
  RunExecutor& operator=(const RunExecutor&) = delete;

  /// Runs a run on worker `worker` (below `workers`; one call at a time per
  /// worker). Never throws: a failure of the run or of the directory is a
  /// failed attempt.
  RunAttempt execute(const RunTask& task, unsigned worker);
  /// Temporary files of interrupted attempts removed so far.
  size_t temporaries_removed() const { return temporaries_removed_; }

 private:
  /// What one worker writes with: its segment of the store and the file its finish marks link to.
  struct Worker {
    Worker(const SweepStore& store, const std::string& stem) : segment(store.store_dir(), stem), stem(stem) {}
    SegmentWriter segment;
    nlohmann::json base_scenario;  ///< the scenario of its segment's first record
    std::string stem;
    std::filesystem::path mark;  ///< empty until the first mark
    int marks_made = 0;
    std::string figures_text;  ///< a run's figures as text (RunOptions::figures_text), its capacity reused
    /// The scenario this worker bound last and its binding: the next
    /// replication of the same point builds from it without reading a key.
    std::shared_ptr<const nlohmann::json> bound_json;
    std::filesystem::path bound_dir;
    std::shared_ptr<const run::BoundScenario> bound;
  };

  RunAttempt claim_and_run(const RunTask& task, unsigned worker);
  RunAttempt run_claimed(const RunTask& task, unsigned worker);
  void mark_finished(const std::string& run_id, Worker& w);

  const SweepStore& store_;
  RunClaims& claims_;
  const SweepJournal& journal_;
  RunSettings settings_;
  std::vector<std::unique_ptr<Worker>> workers_;
  std::atomic<size_t> temporaries_removed_{0};
};

/// Time spent, summed over runs (for the sweep's closing line and BENCHMARKS.md).
struct RunTimes {
  size_t runs = 0;
  double resolve_s = 0.0, run_s = 0.0, simulate_s = 0.0, record_s = 0.0, claim_s = 0.0;
  void add(const RunAttempt& attempt);
  /// "per run: 3.10 ms simulating, 1.20 ms building models and figures, ... ms claiming"
  std::string describe() const;
};

}  // namespace latsim::sweep
