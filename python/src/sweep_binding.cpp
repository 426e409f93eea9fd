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
#include "latsim/scenario/readable.hpp"
#include "latsim/sweep/common.hpp"
#include "latsim/sweep/runner.hpp"

namespace latsim::python {

namespace py = pybind11;
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

// Runs the sweep as `latsim sweep` does (sweep::run_sweep) and says how it went.
SweepOutcome sweep_into(const SweepCall& call, const std::atomic<bool>& stop) {
  const sweep::SweepPlan plan = sweep::read_plan(call.sweep, call.text);
  sweep::SweepRequest request;
  request.sweep_file = call.sweep;
  request.out_dir = call.out_dir;
  request.jobs = call.jobs;
  request.write_ledger = call.ledger;
  request.write_samples = call.samples;
  request.stop = &stop;
  // Which runs keep their traces: the sweep file's "keep", else figures only.
  request.keep = plan.keep().value_or(sweep::KeepPolicy{});
  std::vector<size_t> all(plan.runs().size());
  std::iota(all.begin(), all.end(), size_t{0});
  const sweep::SweepOutcome run = sweep::run_sweep(plan, request, all, true, nullptr);
  if (run.problem)
    throw BadInput(scenario::readable(call.sweep, 2 * scenario::kQuotedChars) + ": " + *run.problem, call.sweep,
                   std::nullopt, *run.problem);
  SweepOutcome outcome;
  if (run.stopped) return outcome;  // the caller raises the signal's exception
  if (run.tally.storage_problem)
    throw std::runtime_error("sweep stopped: " + *run.tally.storage_problem + "; " +
                             std::to_string(run.tally.finished()) + " run(s) finished are kept in " + call.out_dir);
  if (run.tables_problem) throw std::runtime_error("sweep: " + *run.tables_problem);
  outcome.tabled = run.tabled;
  outcome.results_csv = (std::filesystem::path(call.out_dir) / "results.csv").string();
  outcome.runs = plan.runs().size();
  outcome.resumed = run.tally.resumed;
  outcome.ran = run.tally.ran;
  outcome.failures = run.tally.failures;
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
