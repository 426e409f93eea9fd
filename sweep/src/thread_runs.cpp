#include "latsim/sweep/thread_runs.hpp"

#include "latsim/sweep/cost.hpp"
#include "latsim/sweep/execution.hpp"
#include "latsim/sweep/parallel_for.hpp"
#include "latsim/sweep/progress_line.hpp"

namespace latsim::sweep {

SweepTally run_on_threads(const SweepPlan& plan, const std::vector<size_t>& selected,
                          const std::vector<double>& cost_of_run, SweepWorkspace& work, const KeepPolicy& keep,
                          unsigned jobs, const std::atomic<bool>* stop) {
  SweepTally tally;
  std::vector<size_t> pending;
  for (size_t i : selected) {
    if (work.store.is_finished(plan.runs()[i].run_id)) ++tally.resumed;
    else pending.push_back(i);
  }
  pending = longest_first(pending, cost_of_run);
  ProgressLine progress("sweep", selected.size(), tally.resumed);
  std::vector<RunAttempt> attempts(pending.size());
  // Once a stop signal came or the directory cannot take results, starting more runs only fails more.
  std::atomic<bool> storage_unusable{false};
  parallel_for(pending.size(), jobs, [&](size_t i) {
    if (storage_unusable.load() || (stop != nullptr && stop->load())) {
      attempts[i].result = RunAttempt::Result::not_started;
      return;
    }
    attempts[i] = work.executor.execute(RunTask::of(plan, plan.runs()[pending[i]], keep));
    if (attempts[i].storage_unusable) storage_unusable.store(true);
    progress.advance();
  });
  progress.finish();
  tally.add(plan, pending, attempts);
  return tally;
}

}  // namespace latsim::sweep
