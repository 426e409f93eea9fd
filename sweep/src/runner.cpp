#include "latsim/sweep/runner.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <set>

#include "latsim/scenario/readable.hpp"
#include "latsim/sweep/cost.hpp"
#include "latsim/sweep/parallel_for.hpp"
#include "latsim/sweep/tables.hpp"

namespace latsim::sweep {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

SweepOutcome run_sweep(const SweepPlan& plan, const SweepRequest& request, const std::vector<size_t>& selected,
                       bool write_tables, ProgressLine* progress) {
  SweepOutcome out;
  out.selected = selected.size();
  const PointCheck check = check_points(plan, selected, request.jobs, request.max_events, request.stop);
  out.phases.check_s = check.wall_s;
  out.phases.points = check.points;
  // Stopped while checking: nothing is written, not even the directory (the caller says it stopped).
  if (check.stopped) {
    out.stopped = true;
    return out;
  }
  if (check.problem) {
    out.problem = check.problem;
    return out;
  }
  SweepWorkspace work(request);
  write_file_if_changed(work.store.out_dir() / "plan.json", plan.to_json().dump(2) + "\n");
  // One listing tells which runs are done; each is looked at again once claimed.
  const std::set<std::string> finished = work.store.finished_runs();
  std::vector<size_t> pending;
  for (size_t i : selected) {
    if (finished.count(plan.runs()[i].run_id)) ++out.tally.resumed;
    else pending.push_back(i);
  }
  if (progress) progress->resume(out.tally.resumed);
  pending = longest_first(pending, check.cost_of_run);
  std::vector<RunAttempt> attempts(pending.size());
  // Once a stop signal came or the directory cannot take results, starting more runs only fails more.
  std::atomic<bool> storage_unusable{false};
  const auto runs_start = std::chrono::steady_clock::now();
  // A thread takes a point's replications a few at a time: they share its binding.
  std::vector<size_t> point_of_run(pending.size());
  for (size_t i = 0; i < pending.size(); ++i) point_of_run[i] = plan.runs()[pending[i]].point;
  const std::vector<RunChunk> chunks = point_chunks(point_of_run, request.jobs);
  parallel_for(chunks.size(), request.jobs, [&](size_t c, unsigned worker) {
    for (size_t i = chunks[c].begin; i < chunks[c].end; ++i) {
      if (storage_unusable.load(std::memory_order_relaxed) || (request.stop && request.stop->load())) {
        attempts[i].result = RunAttempt::Result::not_started;
        continue;
      }
      attempts[i] = work.executor.execute(RunTask::of(plan, plan.runs()[pending[i]], request.keep), worker);
      if (attempts[i].storage_unusable) storage_unusable.store(true);
      if (progress) progress->advance();
    }
  });
  if (progress) progress->finish();
  out.phases.runs_s = seconds_since(runs_start);
  out.tally.add(plan, pending, attempts);
  out.temporaries = work.executor.temporaries_removed();
  out.stopped = request.stop && request.stop->load();
  if (out.stopped || out.tally.storage_problem || !write_tables) return out;
  const auto tables_start = std::chrono::steady_clock::now();
  try {
    // Reading the records is split in parts, one a thread: never more than can run at once.
    out.tabled = sweep::write_tables(plan, work.store, std::min(request.jobs, available_cpus()), out.temporaries);
    out.tables_written = true;
  } catch (const std::exception& e) {
    out.tables_problem = scenario::readable(e.what());
  }
  out.phases.tables_s = seconds_since(tables_start);
  return out;
}

}  // namespace latsim::sweep
