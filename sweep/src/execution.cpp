#include "latsim/sweep/execution.hpp"

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>

#include "latsim/results/run_files.hpp"
#include "latsim/run/prepared_run.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/sweep/record.hpp"

namespace latsim::sweep {

namespace {

using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

}  // namespace

RunTask RunTask::of(const SweepPlan& plan, const SweepRun& run, const KeepPolicy& keep) {
  // The plan outlives its tasks: they point at its scenario without owning it.
  const std::shared_ptr<const Json> scenario(std::shared_ptr<const Json>{}, &plan.scenario(run));
  return RunTask{run.index,   run.run_id,      run.seed, run.replication,
                 scenario,    plan.base_dir(), keep.keeps_traces(run.index, run.replication)};
}

Json RunTask::to_json() const {
  return {{"index", index}, {"run_id", run_id}, {"seed", seed}, {"replication", replication},
          {"scenario", *scenario}, {"base_dir", base_dir.string()}, {"keep_traces", keep_traces}};
}

RunTask RunTask::from_json(const Json& j) {
  return RunTask{j.at("index").get<size_t>(), j.at("run_id").get<std::string>(), j.at("seed").get<uint64_t>(),
                 j.at("replication").get<uint64_t>(), std::make_shared<const Json>(j.at("scenario")),
                 j.at("base_dir").get<std::string>(), j.at("keep_traces").get<bool>()};
}

Json RunAttempt::to_json() const {
  return {{"result", static_cast<int>(result)}, {"message", message}, {"storage_unusable", storage_unusable},
          {"resolve_s", resolve_s}, {"run_s", run_s}, {"simulate_s", simulate_s}, {"record_s", record_s},
          {"claim_s", claim_s}};
}

RunAttempt RunAttempt::from_json(const Json& j) {
  RunAttempt a;
  a.result = static_cast<Result>(j.at("result").get<int>());
  a.message = j.at("message").get<std::string>();
  a.storage_unusable = j.value("storage_unusable", false);
  a.resolve_s = j.at("resolve_s").get<double>();
  a.run_s = j.at("run_s").get<double>();
  a.simulate_s = j.at("simulate_s").get<double>();
  a.record_s = j.value("record_s", 0.0);
  a.claim_s = j.at("claim_s").get<double>();
  return a;
}

RunExecutor::RunExecutor(const SweepStore& store, RunClaims& claims, const SweepJournal& journal, RunSettings settings,
                         unsigned workers)
    : store_(store), claims_(claims), journal_(journal), settings_(std::move(settings)) {
  // Unique among every writer of every process: host, pid, this executor and the worker.
  static std::atomic<unsigned> executors{0};
  const std::string stem = ClaimHolder::self().host + "." + std::to_string(::getpid()) + "." +
                           std::to_string(executors++) + "-";
  for (unsigned w = 0; w < std::max(1u, workers); ++w)
    workers_.push_back(std::make_unique<Worker>(store, stem + std::to_string(w)));
}

RunExecutor::~RunExecutor() {
  // The marks keep their own names; the file they link to is no longer needed.
  std::error_code ec;
  for (const auto& w : workers_)
    if (!w->mark.empty()) std::filesystem::remove(w->mark, ec);
}

void RunExecutor::mark_finished(const std::string& run_id, Worker& w) {
  if (w.mark.empty()) w.mark = store_.new_mark(w.stem + "." + std::to_string(w.marks_made++));
  if (store_.mark_finished(run_id, w.mark)) return;
  // As many links as one file may have (65,000 on ext4): link to a new one.
  std::error_code ec;
  std::filesystem::remove(w.mark, ec);
  w.mark = store_.new_mark(w.stem + "." + std::to_string(w.marks_made++));
  if (!store_.mark_finished(run_id, w.mark)) throw results::WriteError(w.mark, EMLINK);
}

RunAttempt RunExecutor::execute(const RunTask& task, unsigned worker) {
  try {
    return claim_and_run(task, worker);
  } catch (const std::exception& e) {
    // The sweep directory failed us (a claim or the journal could not be written).
    claims_.release(task.run_id, false);
    RunAttempt attempt;
    attempt.message = e.what();
    attempt.storage_unusable = true;
    return attempt;
  }
}

RunAttempt RunExecutor::claim_and_run(const RunTask& task, unsigned worker) {
  const auto start = Clock::now();
  const ClaimOutcome claim = claims_.claim(task.run_id, worker);
  RunAttempt attempt;
  if (claim.kind == ClaimOutcome::Kind::busy) {
    journal_.record("busy", task.run_id, claim.other.name());
    attempt.result = RunAttempt::Result::busy;
    attempt.message = claim.reason.empty() ? claim.other.name() : claim.reason;
    attempt.claim_s = seconds_since(start);
    return attempt;
  }
  if (claim.kind == ClaimOutcome::Kind::retaken) {
    std::fprintf(stderr, "sweep: warning: run %s: took over the claim of %s: %s\n", task.run_id.c_str(),
                 claim.other.name().c_str(), claim.reason.c_str());
    journal_.record("retake", task.run_id, claim.other.name());
  }
  // Another process may have finished it between our look and our claim.
  if (store_.is_finished(task.run_id)) {
    claims_.release(task.run_id, true);
    journal_.record("skip", task.run_id);
    attempt.result = RunAttempt::Result::finished_already;
    attempt.claim_s = seconds_since(start);
    return attempt;
  }
  temporaries_removed_ += store_.remove_run_temporaries(task.run_id);
  journal_.record("start", task.run_id);
  const double before_run_s = seconds_since(start);
  attempt = run_claimed(task, worker);
  const auto after_run = Clock::now();
  const bool ran = attempt.result == RunAttempt::Result::ran;
  const bool stopped = attempt.result == RunAttempt::Result::stopped;
  journal_.record(ran ? "finish" : stopped ? "stop" : "fail", task.run_id);
  claims_.release(task.run_id, ran);
  attempt.claim_s = before_run_s + seconds_since(after_run);
  return attempt;
}

RunAttempt RunExecutor::run_claimed(const RunTask& task, unsigned worker) {
  RunAttempt attempt;
  run::RunOptions options;
  options.seed = task.seed;
  options.replication = task.replication;
  // Only a run kept in full has files of its own; every run has its record.
  if (task.keep_traces) {
    options.out_dir = store_.run_dir(task.run_id);
    options.staging_dir = store_.staging_dir(task.run_id);
  }
  options.write_samples = settings_.write_samples && task.keep_traces;
  options.write_ledger = settings_.write_ledger && task.keep_traces;
  options.write_timeline = task.keep_traces;
  options.write_images = task.keep_traces;
  options.compact_json = true;
  options.write_presentmon = settings_.write_presentmon && task.keep_traces;
  options.command_line = settings_.command_line;
  options.stop = settings_.stop;
  options.max_events = settings_.max_events;
  Worker& w = *workers_.at(worker);
  // The figures straight to the record's text, without their JSON tree (a kept run writes figures.json from it).
  w.figures_text.clear();
  options.figures_text = &w.figures_text;
  try {
    auto t0 = Clock::now();
    // The same point (its plan's scenario), or an equal scenario (an MPI rank's task carries a copy).
    const bool same = w.bound && w.bound_dir == task.base_dir &&
                      (w.bound_json == task.scenario || *w.bound_json == *task.scenario);
    if (!same) {
      w.bound.reset();  // a scenario that cannot be bound leaves nothing to reuse
      w.bound = std::make_shared<const run::BoundScenario>(
          std::make_shared<const scenario::ScenarioDocument>(
              scenario::ScenarioDocument::from_json(*task.scenario, task.base_dir)),
          nullptr);
      w.bound_json = task.scenario;
      w.bound_dir = task.base_dir;
    }
    attempt.resolve_s = seconds_since(t0);
    t0 = Clock::now();
    options.command_start = Clock::now();
    Json summary = run::PreparedRun(w.bound, options).run();
    attempt.run_s = seconds_since(t0);
    attempt.simulate_s = summary.value("wall_s", 0.0);
    t0 = Clock::now();
    // The scenario as a patch of the one of its segment's first record, which is written whole.
    const bool first = w.segment.starts_segment();
    EncodedRecord record = encode_record(std::move(summary), first ? nullptr : &w.base_scenario, w.figures_text);
    w.segment.append(task.run_id, record.text);
    if (first) w.base_scenario = std::move(record.scenario);
    mark_finished(task.run_id, w);
    attempt.record_s = seconds_since(t0);
    attempt.result = RunAttempt::Result::ran;
  } catch (const scenario::ScenarioError& e) {
    attempt.message = e.what();
  } catch (const run::RunInterrupted& e) {
    attempt.result = RunAttempt::Result::stopped;
    attempt.message = e.what();
  } catch (const results::WriteError& e) {
    attempt.message = e.what();
    attempt.storage_unusable = e.storage_unusable();
  } catch (const std::exception& e) {
    attempt.message = scenario::readable(e.what());
  }
  return attempt;
}

void RunTimes::add(const RunAttempt& attempt) {
  if (attempt.result != RunAttempt::Result::ran) return;
  ++runs;
  resolve_s += attempt.resolve_s;
  run_s += attempt.run_s;
  simulate_s += attempt.simulate_s;
  record_s += attempt.record_s;
  claim_s += attempt.claim_s;
}

std::string RunTimes::describe() const {
  if (runs == 0) return "no runs";
  const double n = static_cast<double>(runs);
  char text[320];
  std::snprintf(text, sizeof text,
                "per run: %.2f ms simulating, %.2f ms building models and figures (and a kept run's files), %.2f ms "
                "recording, %.2f ms reading and binding the scenario, %.2f ms claiming",
                1e3 * simulate_s / n, 1e3 * (run_s - simulate_s) / n, 1e3 * record_s / n, 1e3 * resolve_s / n,
                1e3 * claim_s / n);
  return text;
}

}  // namespace latsim::sweep
