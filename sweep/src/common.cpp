#include "latsim/sweep/common.hpp"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <set>
#include <thread>

#include "latsim/run/prepared_run.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/scenario/json_text.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/sweep/cost.hpp"
#include "latsim/sweep/parallel_for.hpp"

namespace latsim::sweep {

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

// The sweep-file location to blame for a scenario error at `pointer`: the axis
// value that put something bad there, or else the point as a whole.
std::string blame(const SweepPlan& plan, const SweepRun& run, const scenario::ScenarioError& e) {
  for (size_t a = 0; a < plan.axes().size(); ++a) {
    const std::string& axis = plan.axes()[a].pointer;
    if (e.pointer() == axis || e.pointer().rfind(axis + "/", 0) == 0)
      return scenario::readable(plan.value_pointer(a, plan.points()[run.point].value_indices[a]) + ": " + e.what());
  }
  return scenario::readable("/axes: at " + plan.describe(run) + ": " + e.what());
}

}  // namespace

unsigned available_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

SweepPlan read_plan(const std::string& sweep_file, const std::optional<std::string>& text,
                    const std::atomic<bool>* stop) {
  if (!text) return SweepPlan::load(sweep_file, run::resolve_defaults, stop);
  Json sweep;
  try {
    sweep = scenario::parse_json(*text, sweep_file);
  } catch (const scenario::ScenarioError& e) {
    throw SweepError(sweep_file, e.pointer(), e.message());
  }
  return SweepPlan::from_json(sweep, sweep_file, run::resolve_defaults);
}

std::optional<SweepPlan> load_plan(const SweepRequest& request) {
  try {
    return read_plan(request.sweep_file, std::nullopt, request.stop);
  } catch (const PlanStopped&) {
    return std::nullopt;  // not a problem of the file: the caller, seeing the stop, says so
  } catch (const SweepError& e) {
    std::cerr << e.what() << "\n";
    return std::nullopt;
  }
}

bool settle_keep(SweepRequest& request, const SweepPlan& plan) {
  if (!request.keep_given) {
    request.keep = plan.keep().value_or(KeepPolicy{});
  } else {
    try {
      request.keep = KeepPolicy::parse(request.keep_text);
      request.keep.check_runs(plan.runs().size());
    } catch (const std::invalid_argument& e) {
      std::cerr << "latsim sweep: --keep: " << scenario::readable(e.what()) << "\n";
      return false;
    }
  }
  if ((request.write_ledger || request.write_samples || request.write_presentmon) &&
      request.keep.kind == KeepPolicy::Kind::figures)
    std::cerr << "sweep: warning: --ledger, --samples and --presentmon write only for the runs kept in full, and --keep "
                 "figures keeps none: add --keep first, all or runs=I,J\n";
  return true;
}

bool is_sweep_file(const std::string& file) {
  try {
    const Json doc = scenario::read_json_file(file, "file");
    return doc.is_object() && doc.contains("axes") && doc.contains("base");
  } catch (const scenario::ScenarioError&) {
    return false;
  }
}

int validate_sweep(const std::string& file, double max_events, const std::atomic<bool>* stop) {
  SweepRequest request;
  request.sweep_file = file;
  request.stop = stop;
  const auto plan = load_plan(request);
  if (!plan) return stop && stop->load() ? 0 : 2;
  std::vector<size_t> all(plan->runs().size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  const PointCheck check = check_points(*plan, all, available_cpus(), max_events, stop);
  if (check.stopped) return 0;
  const std::string name = scenario::readable(file, 2 * scenario::kQuotedChars);
  if (check.problem) {
    std::cerr << name << ": " << *check.problem << "\n";
    return 2;
  }
  std::printf("%s: ok (sweep of %zu runs, %zu points)\n", name.c_str(), plan->runs().size(), plan->point_count());
  return 0;
}

PointCheck check_points(const SweepPlan& plan, const std::vector<size_t>& run_indices, unsigned jobs,
                        double max_events, const std::atomic<bool>* stop) {
  const auto start = std::chrono::steady_clock::now();
  // One run per point stands for all its replications: they share the scenario.
  std::vector<size_t> firsts;
  std::set<size_t> seen_points;
  for (size_t i : run_indices)
    if (seen_points.insert(plan.runs()[i].point).second) firsts.push_back(i);
  std::vector<std::optional<std::string>> problems(firsts.size());
  std::vector<double> point_cost(plan.point_count(), 0.0);
  std::atomic<bool> stopped{false};
  parallel_for(firsts.size(), jobs, [&](size_t i) {
    if (stop && stop->load(std::memory_order_relaxed)) {
      stopped.store(true, std::memory_order_relaxed);
      return;
    }
    const SweepRun& run = plan.runs()[firsts[i]];
    try {
      auto doc = scenario::ScenarioDocument::from_json(plan.scenario(run), plan.base_dir());
      // One build checks the point and gives its one estimate.
      run::RunOptions options;
      options.max_events = max_events;
      point_cost[run.point] = expected_cost(run::PreparedRun(doc, options).estimate());
    } catch (const scenario::ScenarioError& e) {
      problems[i] = blame(plan, run, e);
    } catch (const std::exception& e) {
      problems[i] = scenario::readable("/axes: at " + plan.describe(run) + ": " + e.what());
    }
  });
  PointCheck check;
  check.stopped = stopped.load();
  for (size_t i = 0; i < firsts.size() && !check.problem; ++i)
    if (problems[i]) check.problem = problems[i];
  check.cost_of_run.assign(plan.runs().size(), 0.0);
  for (size_t i : run_indices) check.cost_of_run[i] = point_cost[plan.runs()[i].point];
  check.points = firsts.size();
  check.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return check;
}

RunSettings run_settings(const SweepRequest& request) {
  RunSettings settings;
  settings.write_samples = request.write_samples;
  settings.write_ledger = request.write_ledger;
  settings.write_presentmon = request.write_presentmon;
  settings.command_line = {"latsim", "sweep", request.sweep_file, "--out", request.out_dir};
  if (request.keep_given) settings.command_line.insert(settings.command_line.end(), {"--keep", request.keep_text});
  if (request.write_samples) settings.command_line.push_back("--samples");
  if (request.write_ledger) settings.command_line.push_back("--ledger");
  if (request.write_presentmon) settings.command_line.push_back("--presentmon");
  settings.stop = request.stop;
  settings.max_events = request.max_events;
  return settings;
}

SweepWorkspace::SweepWorkspace(const SweepRequest& request)
    : store(request.out_dir),
      claims(store.claims_dir(), std::chrono::seconds(request.stale_after_s)),
      journal(store.out_dir(), ClaimHolder::self().host, static_cast<long>(ClaimHolder::self().pid)),
      executor(store, claims, journal, run_settings(request), request.jobs) {}

void SweepTally::add(const SweepPlan& plan, const std::vector<size_t>& indices, const std::vector<RunAttempt>& attempts) {
  std::vector<size_t> order(indices.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return indices[a] < indices[b]; });
  for (size_t i : order) {
    const RunAttempt& attempt = attempts[i];
    const SweepRun& run = plan.runs()[indices[i]];
    times.add(attempt);
    switch (attempt.result) {
      case RunAttempt::Result::ran: ++ran; break;
      case RunAttempt::Result::finished_already: ++finished_elsewhere; break;
      case RunAttempt::Result::busy:
        ++busy;
        if (std::find(holders.begin(), holders.end(), attempt.message) == holders.end()) holders.push_back(attempt.message);
        break;
      case RunAttempt::Result::failed:
        failures.push_back(run.run_id + " (" + plan.describe(run) + "): " + attempt.message);
        if (attempt.storage_unusable && !storage_problem) storage_problem = attempt.message;
        break;
      case RunAttempt::Result::stopped: ++stopped; break;
      case RunAttempt::Result::not_started: ++not_started; break;
    }
  }
}

std::string SweepTally::counts() const {
  char text[200];
  int n = std::snprintf(text, sizeof text, "(%zu resumed, %zu run now, ", resumed, ran);
  if (finished_elsewhere) n += std::snprintf(text + n, sizeof text - n, "%zu finished by other processes, ", finished_elsewhere);
  if (busy) n += std::snprintf(text + n, sizeof text - n, "%zu left to other processes, ", busy);
  if (stopped) n += std::snprintf(text + n, sizeof text - n, "%zu stopped midway, ", stopped);
  if (not_started) n += std::snprintf(text + n, sizeof text - n, "%zu not started, ", not_started);
  std::snprintf(text + n, sizeof text - n, "%zu failed)", failures.size());
  return text;
}

void SweepTally::print_notes(size_t temporaries_removed) const {
  if (temporaries_removed > 0)
    std::cerr << "sweep: removed " << temporaries_removed << " unfinished temporary file(s) of an interrupted sweep\n";
  // When the directory cannot be written every failure says the same: one line says it all.
  if (storage_problem) {
    std::cerr << "sweep: stopped: " << *storage_problem << "; " << finished() << " run(s) finished, " << failures.size()
              << " failed, " << not_started << " not started; make room (or make the directory writable) and run "
              << "the same command again to finish\n";
  } else {
    for (const auto& failure : failures) std::cerr << "sweep: run failed: " << failure << "\n";
  }
  if (busy > 0) {
    std::cerr << "sweep: " << busy << " run(s) left to the processes that hold them:";
    for (const auto& holder : holders) std::cerr << " " << holder << (&holder == &holders.back() ? "" : ",");
    std::cerr << "\n";
  }
}

void PhaseTimes::print(const RunTimes& times, unsigned workers) const {
  // Points are built on up to `workers` threads at once.
  const double threads = static_cast<double>(std::clamp<size_t>(points, 1, std::max(1u, workers)));
  const double per_point_ms = points ? 1e3 * check_s * threads / static_cast<double>(points) : 0.0;
  std::printf("sweep: timings: plan %.3f s, checking %zu point(s) %.3f s (%.2f ms each on one thread), runs %.3f s, "
              "tables %.3f s\n",
              plan_s, points, check_s, per_point_ms, runs_s, tables_s);
  std::printf("sweep: %s\n", times.describe().c_str());
}

}  // namespace latsim::sweep
