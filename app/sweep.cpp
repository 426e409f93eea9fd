// latsim sweep: runs every point of a sweep file, resumably and in parallel,
// on this machine's threads, as one shard of a batch scheduler's job array, or
// on the ranks of an MPI job, and gathers the results into results.csv and
// results.sqlite.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/sweep/common.hpp"
#include "latsim/sweep/mpi.hpp"
#include "latsim/sweep/progress_line.hpp"
#include "latsim/sweep/runner.hpp"
#include "latsim/sweep/shard.hpp"
#include "latsim/sweep/tables.hpp"
#include "stop_signals.hpp"

namespace latsim::app {

using namespace sweep;  // the sweep engine this command drives

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Runs the plan's runs that are in `shard` (all of them without one) on this
// machine's threads, then writes the tables unless this is one shard of many.
int sweep_here(const SweepRequest& request, const SweepPlan& plan, const std::optional<Shard>& shard,
               PhaseTimes phases) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<size_t> selected;
  for (const auto& run : plan.runs())
    if (!shard || shard->contains(run.index)) selected.push_back(run.index);
  const StopSignals& signals = StopSignals::installed();
  SweepRequest stoppable = request;
  stoppable.stop = &signals.flag();
  const bool one_of_many = shard && shard->count > 1;
  ProgressLine progress("sweep", selected.size());
  const SweepOutcome out = run_sweep(plan, stoppable, selected, !one_of_many, &progress);
  phases.check_s = out.phases.check_s;
  phases.points = out.phases.points;
  phases.runs_s = out.phases.runs_s;
  phases.tables_s = out.phases.tables_s;
  if (out.problem) {
    std::cerr << request.sweep_file << ": " << *out.problem << "\n";
    return kExitBadInput;
  }
  const SweepTally& tally = out.tally;
  if (signals.requested()) {
    if (StopSignals::first_word())
      std::fprintf(stderr,
                   "sweep: stopped by %s: %zu of %zu run(s) finished %s, none partly written; run the same command "
                   "again to finish\n",
                   signals.name(), tally.finished(), selected.size(), tally.counts().c_str());
    return signals.exit_code();
  }
  if (tally.storage_problem) {
    tally.print_notes(out.temporaries);
    return kExitFailure;
  }
  if (one_of_many) {
    const std::string from = shard->source == request.shard ? "" : " (" + shard->source + ")";
    std::printf("sweep: shard %zu/%zu%s: %zu of %zu runs %s on %u thread(s) in %.2f s; "
                "latsim sweep --collect writes the tables once every shard is done\n",
                shard->index, shard->count, from.c_str(), selected.size(), plan.runs().size(),
                tally.counts().c_str(), request.jobs, seconds_since(start));
    tally.print_notes(out.temporaries);
    if (request.timings) phases.print(tally.times, request.jobs);
    return tally.failures.empty() ? kExitOk : kExitFailure;
  }
  if (out.tables_problem) {
    std::fprintf(stderr, "sweep: %s; the %zu finished run(s) are kept: make room and run the same command again "
                         "(or latsim sweep --collect) to write the tables\n",
                 out.tables_problem->c_str(), tally.finished());
    return kExitFailure;
  }
  std::printf("sweep: %zu runs %s on %u thread(s) in %.2f s -> %s\n", plan.runs().size(), tally.counts().c_str(),
              request.jobs, seconds_since(start), (std::filesystem::path(request.out_dir) / "results.csv").c_str());
  tally.print_notes(out.temporaries);
  if (request.timings) phases.print(tally.times, request.jobs);
  return tally.failures.empty() && out.tabled == plan.runs().size() ? kExitOk : kExitFailure;
}

// Writes the tables of a sweep that shards ran, and names every run still missing.
int collect(const SweepRequest& request, const SweepPlan& plan) {
  if (!std::filesystem::is_directory(std::filesystem::path(request.out_dir) / "runs")) {
    std::cerr << request.out_dir << ": not a sweep directory (no runs/ in it)\n";
    return kExitBadInput;
  }
  SweepStore store(request.out_dir);
  RunClaims claims(store.claims_dir(), std::chrono::seconds(request.stale_after_s));
  size_t temporaries = 0;
  const auto start = std::chrono::steady_clock::now();
  const size_t gathered = write_tables(plan, store, available_cpus(), temporaries);
  const double tables_s = seconds_since(start);
  const auto missing = missing_runs(plan, store, claims);
  std::printf("sweep: collected %zu of %zu runs -> %s\n", gathered, plan.runs().size(),
              (store.out_dir() / "results.csv").c_str());
  if (request.timings) std::printf("sweep: timings: tables %.3f s\n", tables_s);
  if (missing.empty()) return kExitOk;
  std::cerr << "sweep: " << missing.size() << " run(s) not finished; run their shards again:\n";
  constexpr size_t kShown = 20;
  for (size_t i = 0; i < missing.size() && i < kShown; ++i) std::cerr << "  missing " << missing[i] << "\n";
  if (missing.size() > kShown) std::cerr << "  ... and " << missing.size() - kShown << " more\n";
  return kExitFailure;
}

// Builds every point without running or writing anything, for a batch
// script to call once before it submits many tasks.
int check_only(const SweepRequest& request, const SweepPlan& plan) {
  std::vector<size_t> all(plan.runs().size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  const PointCheck check = check_points(plan, all, request.jobs, request.max_events);
  if (check.problem) {
    std::cerr << request.sweep_file << ": " << *check.problem << "\n";
    return kExitBadInput;
  }
  size_t finished = 0;
  const std::set<std::string> done = finished_runs_in(request.out_dir);
  for (const auto& run : plan.runs()) finished += done.count(run.run_id);
  std::printf("sweep: %s: %zu runs (%zu points x %llu replications), every point valid; %zu finished in %s\n",
              request.sweep_file.c_str(), plan.runs().size(), plan.point_count(),
              static_cast<unsigned long long>(plan.replications()), finished, request.out_dir.c_str());
  return kExitOk;
}

}  // namespace

int command_sweep(int argc, char** argv) {
  CLI::App app{"Runs every point of a parameter sweep (resumable, parallel, on a cluster by shards or MPI) and "
               "gathers results.csv and results.sqlite"};
  app.name("latsim sweep");
  SweepRequest request;
  app.add_option("sweep", request.sweep_file, "Sweep file (JSON: base, axes, mode, replications, seed, overrides)")
      ->required();
  app.add_option("-o,--out", request.out_dir, "Output directory; an existing sweep there is resumed")->required();
  auto* jobs = app.add_option("-j,--jobs", request.jobs,
                              "Runs at once (default: the CPUs this process may use; with --mpi, 1 per rank)")
                   ->check(CLI::Range(1u, 4096u));
  app.add_flag("--samples", request.write_samples, "Also write samples.csv for the runs --keep keeps in full");
  app.add_flag("--ledger", request.write_ledger, "Also write frames.csv, the ledger, for the runs --keep keeps in full");
  auto* keep = app.add_option("--keep", request.keep_text,
                 "Which runs also keep their traces (timeline, frames, ledger, samples): figures (none; the default "
                 "unless the sweep file's \"keep\" says otherwise), first (replication 0 of each point), all, or "
                 "runs=I,J,... (plan positions from 0)");
  app.add_flag("--presentmon", request.write_presentmon, "Also write presentmon.csv for the runs --keep keeps in full");
  auto* shard = app.add_option("--shard", request.shard,
                               "Run only the runs whose plan position modulo N is I (I/N, from 0), or 'env': the "
                               "array task of Slurm or Grid Engine; tables are left to --collect");
  auto* collect_flag = app.add_flag("--collect", request.collect,
                                    "Run nothing: write the tables of the finished runs and name the missing ones");
  auto* check = app.add_flag("--check", request.check,
                             "Run and write nothing: check every point of the sweep and count the finished runs");
  auto* mpi = app.add_flag("--mpi", request.mpi, "Under mpirun: rank 0 hands runs out to every rank, then writes the tables");
  app.add_flag("--timings", request.timings, "Also print where the time per run went");
  app.add_option("--stale-after", request.stale_after_s,
                 "Seconds without a heartbeat after which another host's claim on a run is stale")
      ->check(CLI::Range(1u, 7u * 24u * 3600u))
      ->capture_default_str();
  add_max_events_option(app, request.max_events);
  shard->excludes(collect_flag);
  check->excludes(shard);
  check->excludes(collect_flag);
  check->excludes(mpi);
  mpi->excludes(shard);
  mpi->excludes(collect_flag);
  if (const auto rc = parse_options(app, argc, argv)) return *rc;
  if (const auto rc = refuse_out_dir("latsim sweep", request.out_dir)) return *rc;
  request.keep_given = keep->count() > 0;
  if (!*jobs) request.jobs = request.mpi ? 1u : available_cpus();

  std::optional<Shard> slice;
  // Given, even empty: "--shard ''" ran the whole sweep, as if not given.
  if (shard->count() > 0) {
    try {
      slice = parse_shard(request.shard);
    } catch (const std::invalid_argument& e) {
      std::cerr << "latsim sweep: " << e.what() << "\n";
      return kExitBadInput;
    }
  }
  try {
    if (request.mpi) {
      const StopSignals& signals = StopSignals::installed();
      SweepRequest stoppable = request;
      stoppable.stop = &signals.flag();
      return sweep_mpi(stoppable, [&signals](bool lead) {
        if (lead && StopSignals::first_word())
          std::fprintf(stderr, "sweep: stopped by %s: no run started since, none partly written; run the same "
                               "command again to finish\n", signals.name());
        else
          (void)StopSignals::first_word();  // the other ranks stay silent, their watchdog too
        return signals.exit_code();
      });
    }
    const auto start = std::chrono::steady_clock::now();
    const auto plan = load_plan(request);
    if (!plan || !settle_keep(request, *plan)) return kExitBadInput;
    if (request.check) return check_only(request, *plan);
    if (request.collect) return collect(request, *plan);
    PhaseTimes phases;
    phases.plan_s = seconds_since(start);
    return sweep_here(request, *plan, slice, phases);
  } catch (const std::exception& e) {
    std::cerr << "sweep: " << e.what() << "\n";
    return kExitFailure;
  }
}

}  // namespace latsim::app
