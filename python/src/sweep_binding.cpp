// _latsim.sweep: every run of a sweep (a file, or JSON text standing for one)
// into a sweep directory on this machine's threads, as `latsim sweep` does
// without --shard or --mpi, and the tables written from them.
#include <atomic>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "errors.hpp"
#include "interruptible.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/json_text.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/sweep/common.hpp"
#include "latsim/sweep/tables.hpp"
#include "latsim/sweep/thread_runs.hpp"

namespace latsim::python {

namespace py = pybind11;
using Json = nlohmann::json;

namespace {

// What the package passes for one sweep.
struct SweepCall {
  std::string sweep;                // the file, or the name standing for it when `text` is given
  std::optional<std::string> text;  // the sweep as JSON text
  std::string out_dir;
  unsigned jobs = 1;
  bool ledger = false;
  bool samples = false;
};

// How the sweep went.
struct SweepOutcome {
  std::string results_csv;
  size_t runs = 0, resumed = 0, ran = 0, tabled = 0;
  std::vector<std::string> failures;
};

sweep::SweepPlan plan_of(const SweepCall& call) {
  if (!call.text) return sweep::SweepPlan::load(call.sweep, run::resolve_defaults);
  return sweep::SweepPlan::from_json(scenario::parse_json(*call.text, call.sweep), call.sweep, run::resolve_defaults);
}

// Checks every point, then runs the unfinished runs longest first and writes the tables.
SweepOutcome sweep_into(const SweepCall& call, const std::atomic<bool>& stop) {
  const sweep::SweepPlan plan = plan_of(call);
  std::vector<size_t> all(plan.runs().size());
  std::iota(all.begin(), all.end(), size_t{0});
  const sweep::PointCheck check = sweep::check_points(plan, all, call.jobs);
  if (check.problem)
    throw BadInput(scenario::readable(call.sweep, 2 * scenario::kQuotedChars) + ": " + *check.problem, call.sweep,
                   std::nullopt, *check.problem);
  sweep::SweepRequest request;
  request.sweep_file = call.sweep;
  request.out_dir = call.out_dir;
  request.jobs = call.jobs;
  request.write_ledger = call.ledger;
  request.write_samples = call.samples;
  request.stop = &stop;
  sweep::SweepWorkspace work(request);
  sweep::write_file_if_changed(work.store.out_dir() / "plan.json", plan.to_json().dump(2) + "\n");

  // Which runs keep their traces: the sweep file's "keep", else figures only.
  const sweep::KeepPolicy keep = plan.keep().value_or(sweep::KeepPolicy{});
  const sweep::SweepTally tally = sweep::run_on_threads(plan, all, check.cost_of_run, work, keep, call.jobs, &stop);
  SweepOutcome outcome;
  if (stop.load()) return outcome;  // the caller raises the signal's exception
  if (tally.storage_problem)
    throw std::runtime_error("sweep stopped: " + *tally.storage_problem + "; " + std::to_string(tally.finished()) +
                             " run(s) finished are kept in " + call.out_dir);
  size_t temporaries = work.executor.temporaries_removed();
  outcome.tabled = sweep::write_tables(plan, work.store, call.jobs, temporaries);
  outcome.results_csv = (work.store.out_dir() / "results.csv").string();
  outcome.runs = plan.runs().size();
  outcome.resumed = tally.resumed;
  outcome.ran = tally.ran;
  outcome.failures = tally.failures;
  return outcome;
}

py::dict sweep(const SweepCall& call) {
  SweepOutcome outcome;
  try {
    run_interruptibly([&](const std::atomic<bool>& stop) { outcome = sweep_into(call, stop); });
  } catch (const scenario::ScenarioError& e) {
    throw BadInput::of(e, call.sweep);
  } catch (const sweep::SweepError& e) {
    throw BadInput(e.what(), call.sweep, e.pointer(), e.message());
  }
  py::dict out;
  out["results_csv"] = outcome.results_csv;
  out["runs"] = outcome.runs;
  out["resumed"] = outcome.resumed;
  out["ran"] = outcome.ran;
  out["tabled"] = outcome.tabled;
  out["failures"] = outcome.failures;
  return out;
}

}  // namespace

void add_sweep(py::module_& m) {
  m.def(
      "sweep",
      [](std::string sweep_file, std::optional<std::string> text, std::string out_dir, unsigned jobs, bool ledger,
         bool samples) {
        return sweep(SweepCall{std::move(sweep_file), std::move(text), std::move(out_dir), jobs, ledger, samples});
      },
      py::arg("sweep"), py::arg("text"), py::arg("out_dir"), py::arg("jobs"), py::arg("ledger"), py::arg("samples"),
      "Runs every unfinished run of a sweep into out_dir and writes its tables; returns where results.csv is and "
      "how the runs went.");
}

}  // namespace latsim::python
