// latsim sweep: runs every point of a sweep file, resumably and in parallel,
// and gathers the results into results.csv and results.sqlite.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "latsim/pipelines/runner.hpp"
#include "latsim/scenario/config.hpp"
#include "parallel_for.hpp"
#include "progress_line.hpp"
#include "results_db.hpp"
#include "run_table.hpp"
#include "sweep_plan.hpp"
#include "sweep_store.hpp"

namespace latsim::app {

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

/// What `latsim sweep` was asked to do.
struct SweepRequest {
  std::string sweep_file;
  std::string out_dir;
  unsigned jobs = 0;
  bool write_samples = false;
  bool write_ledger = false;
};

Json resolve_defaults(const Json& scenario, const fs::path& base_dir) {
  auto doc = scenario::ScenarioDocument::from_json(scenario, base_dir);
  pipelines::validate_scenario(doc);
  return doc.resolved();
}

// The sweep-file location to blame for a scenario error at `pointer`: the axis
// value that put something bad there, or else the point as a whole.
std::string blame(const SweepPlan& plan, const SweepRun& run, const scenario::ScenarioError& e) {
  for (size_t a = 0; a < plan.axes().size(); ++a) {
    const std::string& axis = plan.axes()[a].pointer;
    if (e.pointer() == axis || e.pointer().rfind(axis + "/", 0) == 0)
      return plan.value_pointer(a, run.value_indices[a]) + ": " + e.pointer() + ": " + e.message();
  }
  return "/axes: at " + plan.describe(run) + ": " + e.pointer() + ": " + e.message();
}

// Builds every distinct scenario of the plan without running it, so a bad
// value is reported before anything is written. Returns the first problem in plan order.
std::optional<std::string> validate_points(const SweepPlan& plan, unsigned jobs) {
  std::vector<const SweepRun*> firsts;
  for (const auto& run : plan.runs())
    if (run.replication == 0) firsts.push_back(&run);
  std::vector<std::optional<std::string>> problems(firsts.size());
  parallel_for(firsts.size(), jobs, [&](size_t i) {
    try {
      auto doc = scenario::ScenarioDocument::from_json(firsts[i]->scenario, plan.base_dir());
      pipelines::validate_scenario(doc);
    } catch (const scenario::ScenarioError& e) {
      problems[i] = blame(plan, *firsts[i], e);
    } catch (const std::exception& e) {
      problems[i] = "/axes: at " + plan.describe(*firsts[i]) + ": " + e.what();
    }
  });
  for (auto& problem : problems)
    if (problem) return problem;
  return std::nullopt;
}

// Runs every unfinished run; returns one message per failed run, in plan order.
std::vector<std::string> execute(const SweepPlan& plan, const SweepStore& store, const SweepRequest& request,
                                 const std::vector<std::string>& command_line) {
  const auto& runs = plan.runs();
  std::vector<size_t> pending;
  for (const auto& run : runs)
    if (!store.is_finished(run.run_id)) pending.push_back(run.index);
  ProgressLine progress("sweep", runs.size(), runs.size() - pending.size());
  std::vector<std::optional<std::string>> failures(pending.size());
  parallel_for(pending.size(), request.jobs, [&](size_t i) {
    const SweepRun& run = runs[pending[i]];
    pipelines::RunOptions options;
    options.seed = run.seed;
    options.replication = run.replication;
    options.out_dir = store.run_dir(run.run_id);
    options.write_samples = request.write_samples;
    options.write_ledger = request.write_ledger;
    options.command_line = command_line;
    try {
      auto doc = scenario::ScenarioDocument::from_json(run.scenario, plan.base_dir());
      (void)pipelines::run_scenario(doc, options);
    } catch (const scenario::ScenarioError& e) {
      failures[i] = run.run_id + " (" + plan.describe(run) + "): " + e.pointer() + ": " + e.message();
    } catch (const std::exception& e) {
      failures[i] = run.run_id + " (" + plan.describe(run) + "): " + e.what();
    }
    progress.advance();
  });
  progress.finish();
  std::vector<std::string> messages;
  for (auto& failure : failures)
    if (failure) messages.push_back(*failure);
  return messages;
}

// Reads every finished run's summary in plan order and writes the two result tables.
size_t gather(const SweepPlan& plan, const SweepStore& store) {
  std::vector<RunRecord> records;
  for (const auto& run : plan.runs()) {
    auto summary = store.load_summary(run.run_id);
    if (!summary) continue;
    RunRecord record{run.run_id, run.point, run.seed, run.replication, {}, std::move(*summary)};
    for (size_t a = 0; a < plan.axes().size(); ++a) record.values.push_back(plan.axes()[a].values[run.value_indices[a]]);
    records.push_back(std::move(record));
  }
  std::vector<std::string> pointers;
  for (const auto& axis : plan.axes()) pointers.push_back(axis.pointer);
  pipelines::write_file_atomically(store.out_dir() / "results.csv", results_csv(pointers, records));
  write_results_db(store.out_dir() / "results.sqlite", pointers, records);
  return records.size();
}

// The command line each run records: the sweep as invoked, less -j, which
// must not make one run's files differ from another's.
std::vector<std::string> recorded_command_line(const SweepRequest& request) {
  std::vector<std::string> line{"latsim", "sweep", request.sweep_file, "--out", request.out_dir};
  if (request.write_samples) line.push_back("--samples");
  if (request.write_ledger) line.push_back("--ledger");
  return line;
}

}  // namespace

int command_sweep(int argc, char** argv) {
  CLI::App app{"Runs every point of a parameter sweep (resumable, parallel) and gathers results.csv and results.sqlite"};
  app.name("latsim sweep");
  SweepRequest request;
  request.jobs = std::max(1u, std::thread::hardware_concurrency());
  app.add_option("sweep", request.sweep_file, "Sweep file (JSON: base, axes, mode, replications, seed, overrides)")
      ->required();
  app.add_option("-o,--out", request.out_dir, "Output directory; an existing sweep there is resumed")->required();
  app.add_option("-j,--jobs", request.jobs, "Runs in parallel (default: number of cores)")->check(CLI::Range(1u, 4096u));
  app.add_flag("--samples", request.write_samples, "Also write each run's samples.csv");
  app.add_flag("--ledger", request.write_ledger, "Also write each run's frames.csv ledger");
  if (const auto rc = parse_options(app, argc, argv)) return *rc;

  std::optional<SweepPlan> plan;
  try {
    plan = SweepPlan::load(request.sweep_file, resolve_defaults);
  } catch (const SweepError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  }
  if (auto problem = validate_points(*plan, request.jobs)) {
    std::cerr << request.sweep_file << ": " << *problem << "\n";
    return kExitBadInput;
  }

  const auto start = std::chrono::steady_clock::now();
  try {
    SweepStore store(request.out_dir);
    const size_t stale = store.remove_temporaries();
    if (stale > 0) std::cerr << "sweep: removed " << stale << " unfinished temporary file(s) of an interrupted sweep\n";
    pipelines::write_file_atomically(store.out_dir() / "plan.json", plan->to_json().dump(2) + "\n");
    size_t resumed = 0;
    for (const auto& run : plan->runs()) resumed += store.is_finished(run.run_id) ? 1 : 0;
    const auto failures = execute(*plan, store, request, recorded_command_line(request));
    const size_t gathered = gather(*plan, store);
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("sweep: %zu runs (%zu resumed, %zu run now, %zu failed) on %u thread(s) in %.2f s -> %s\n",
                plan->runs().size(), resumed, plan->runs().size() - resumed - failures.size(), failures.size(),
                request.jobs, wall_s, (store.out_dir() / "results.csv").c_str());
    for (const auto& failure : failures) std::cerr << "sweep: run failed: " << failure << "\n";
    if (!failures.empty() || gathered != plan->runs().size()) return kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "sweep: " << e.what() << "\n";
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace latsim::app
