// What the backends of `latsim sweep` (threads, shards, MPI ranks) share:
// the request, checking the plan's scenarios, and accounting for the runs.
#pragma once

#include <atomic>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "latsim/run/runner.hpp"
#include "latsim/sweep/execution.hpp"
#include "latsim/sweep/plan.hpp"

namespace latsim::sweep {

/// What `latsim sweep` was asked to do.
struct SweepRequest {
  std::string sweep_file;
  std::string out_dir;
  unsigned jobs = 1;
  bool write_samples = false;
  bool write_ledger = false;
  std::string keep_text;      ///< --keep text, when keep_given
  bool keep_given = false;    ///< false: the sweep file's "keep" key, else figures
  KeepPolicy keep;            ///< which runs keep their traces (settled by settle_keep)
  bool write_presentmon = false;  ///< each run's presentmon.csv (off: a sweep keeps figures)
  std::string shard;          ///< --shard text: "I/N" or "env"; empty: the whole plan
  bool collect = false;       ///< --collect: run nothing, write the tables
  bool check = false;         ///< --check: run nothing, write nothing: check every point
  bool mpi = false;           ///< --mpi: rank 0 hands runs out to the ranks of an MPI job
  bool timings = false;       ///< --timings: also print where the time per run went
  unsigned stale_after_s = 600;
  double max_events = run::kDefaultMaxEvents;  ///< --max-events: a run's largest event estimate (0: no limit)  ///< a claim from another host without a heartbeat this long is stale
  const std::atomic<bool>* stop = nullptr;  ///< a stop signal's flag: runs end at their next event
};

/// The CPUs this process may run on (its affinity mask, which batch
/// schedulers restrict to the allocation), at least 1.
unsigned available_cpus();

/// Reads a sweep file (or `text`, the sweep as JSON text, `sweep_file`
/// standing for its file in messages); throws SweepError.
SweepPlan read_plan(const std::string& sweep_file, const std::optional<std::string>& text = std::nullopt,
                    const std::atomic<bool>* stop = nullptr);

/// Reads the sweep file; on bad input prints the one-line error and returns nothing
/// (nothing either, without a word, once *request.stop is set).
std::optional<SweepPlan> load_plan(const SweepRequest& request);

/// Settles request.keep from --keep or else the plan's "keep" key; on a bad
/// value prints the one-line error and returns false (nothing is written).
/// Warns when --ledger or --samples is given but no run keeps its traces.
bool settle_keep(SweepRequest& request, const SweepPlan& plan);

/// Whether `file` holds a sweep (a JSON object with "axes" and "base") rather
/// than a scenario; false when it is not readable JSON (the scenario reader
/// then says why).
bool is_sweep_file(const std::string& file);

/// `latsim validate` of a sweep file: reads it and builds every distinct
/// point without running or writing anything; prints "FILE: ok (sweep of N
/// runs, M points)" or the first problem in one line. Returns the exit code;
/// once *stop is set it stops building points and returns 0 without a word
/// (the caller says that it stopped).
int validate_sweep(const std::string& file, double max_events = run::kDefaultMaxEvents,
                   const std::atomic<bool>* stop = nullptr);

/// The outcome of building the scenarios of some runs without running them.
struct PointCheck {
  std::optional<std::string> problem;  ///< the first bad point in plan order, as the error line shows it
  std::vector<double> cost_of_run;     ///< expected cost by plan index (0 for runs not checked)
  size_t points = 0;                   ///< distinct points built
  double wall_s = 0.0;                 ///< building them took
  bool stopped = false;                ///< a stop signal came first: the points are not all built
};

/// Builds every distinct scenario among `run_indices` (once per point) on
/// `jobs` threads, so that a bad value is reported before anything is written,
/// and estimates each run's cost from the resolved scenario; a point whose
/// event estimate is above max_events (0: no limit) is a problem. Once *stop
/// is set no further point is built (a sweep of 1e5 points takes seconds).
PointCheck check_points(const SweepPlan& plan, const std::vector<size_t>& run_indices, unsigned jobs,
                        double max_events = run::kDefaultMaxEvents, const std::atomic<bool>* stop = nullptr);

/// What each run records and writes: the command line recorded is the sweep
/// as invoked less -j, --shard, --mpi and the like, which must not make one
/// run's files differ from another's.
RunSettings run_settings(const SweepRequest& request);

/// The sweep directory as one process works in it: its claims, its journal
/// and the executor that runs runs there on request.jobs threads. Creates the directory.
struct SweepWorkspace {
  explicit SweepWorkspace(const SweepRequest& request);

  SweepStore store;
  RunClaims claims;
  SweepJournal journal;
  RunExecutor executor;
};

/// How the runs of one process (or of a whole MPI job) went.
struct SweepTally {
  size_t resumed = 0;             ///< finished before we started
  size_t ran = 0;
  size_t finished_elsewhere = 0;  ///< finished by another process while we waited to claim it
  size_t busy = 0;                ///< held by another live process: left to it
  size_t stopped = 0;             ///< ended midway by a stop signal (nothing of them kept)
  size_t not_started = 0;         ///< not begun because the sweep was stopping
  std::vector<std::string> failures;  ///< one message per failed run, in plan order
  /// Why the sweep directory could not be written, when that stopped the sweep.
  std::optional<std::string> storage_problem;
  std::vector<std::string> holders;   ///< who held the busy runs, distinct
  RunTimes times;

  /// Adds the attempts (indexed like `indices`) in plan order.
  void add(const SweepPlan& plan, const std::vector<size_t>& indices, const std::vector<RunAttempt>& attempts);
  /// "(3 resumed, 29 run now, 0 failed)", with the rarer counts only when not zero.
  std::string counts() const;
  /// Runs finished now or before.
  size_t finished() const { return resumed + ran + finished_elsewhere; }
  /// Prints the failures, the runs left to others and removed temporaries.
  void print_notes(size_t temporaries_removed) const;
};

/// Where a sweep process's time went, printed with --timings.
struct PhaseTimes {
  double plan_s = 0.0;    ///< reading the sweep file and expanding the plan
  double check_s = 0.0;   ///< building every point once (PointCheck)
  size_t points = 0;
  double runs_s = 0.0;    ///< running the runs
  double tables_s = 0.0;  ///< writing results.csv and results.sqlite
  /// Two lines: the phases, and the time per run from `times`.
  void print(const RunTimes& times, unsigned workers) const;
};

}  // namespace latsim::sweep
