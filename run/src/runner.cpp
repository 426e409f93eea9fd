#include "latsim/run/runner.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "latsim/des/stop_token.hpp"
#include "latsim/run/builder.hpp"
#include "latsim/run/builtin_pipelines.hpp"
#include "latsim/run/event_budget.hpp"
#include "latsim/run/prepared_run.hpp"
#include "latsim/run/result_writer.hpp"

namespace latsim::run {

using Json = nlohmann::json;

namespace {

// Simulated seconds for a message, as precise as a picosecond needs.
std::string seconds_text(des::Time t) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.12g s", t.to_seconds());
  return buf;
}

// Builds of runs made by this process (builds_made()).
std::atomic<uint64_t> builds_made_{0};

// Progress is reported this often; checking the clock costs a few ns per call.
constexpr uint64_t kEventsPerProgress = 1 << 14;

// Runs the simulation; a model that throws becomes a RunFailure naming it
// and the simulated time, a stop request a RunInterrupted. A result file
// streamed during the run (the timeline) that cannot be written stays a
// WriteError: the storage failed, not the model.
void simulate(Run& run) {
  try {
    run.host->start(run.duration);
    run.display->start(run.duration);
    run.sim.run_until(run.duration);
  } catch (const results::WriteError&) {
    throw;
  } catch (const des::StopRequested&) {
    // A loop inside an event (the classification of head motion up to a far
    // photon time) saw the stop request before the kernel did.
    throw RunInterrupted(run.sim.now(), run.duration);
  } catch (const std::exception& e) {
    const auto kind = run.sim.failed_kind();
    const std::string name = kind ? run.sim.kind_name(*kind) : std::string("start");
    throw RunFailure(name.substr(0, name.find('.')), run.sim.now(),
                     dynamic_cast<const std::bad_alloc*>(&e) ? std::string("out of memory") : std::string(e.what()));
  }
  if (run.sim.interrupted()) throw RunInterrupted(run.sim.now(), run.duration);
  if (run.ctx->ended_early) {
    // The figures cover the time simulated; the warning says why it is short.
    run.duration = run.sim.now();  // the pipeline reads it (RunContext::duration), not a copy
    run.recording->book().warn(*run.ctx->ended_early);
  }
}

// Copies what the run recorded into `tables`.
void keep_tables(const Run& run, RunTables& tables) {
  const results::Ledger& ledger = run.recording->ledger();
  tables.frames = ledger.frames();
  tables.fields = ledger.fields();
  tables.tracker = ledger.tracker();
  tables.samples = run.recording->sample_log().samples();
  // The stage intervals (the JSON's counters and flows are not timeline.csv's rows).
  for (const results::Timeline::Entry& e : run.timeline.entries())
    if (e.kind == results::Timeline::Kind::interval) tables.timeline.push_back(e);
  tables.timeline_dropped = run.timeline.dropped();
}

}  // namespace

RunFailure::RunFailure(std::string model, des::Time at, const std::string& cause)
    : std::runtime_error("run failed in " + model + " at simulated t = " + seconds_text(at) + ": " + cause),
      model_(std::move(model)),
      at_(at) {}

RunInterrupted::RunInterrupted(des::Time at, des::Time end)
    : std::runtime_error("interrupted at simulated t = " + seconds_text(at) + " of " + seconds_text(end)), at_(at) {}

RunInterrupted::RunInterrupted(const std::string& phase, des::Time end)
    : std::runtime_error("interrupted " + phase + ", after simulating " + seconds_text(end)), at_(end) {}

std::string latsim_version() { return LATSIM_VERSION; }
std::string latsim_git_revision() { return LATSIM_GIT_REVISION; }

const scenario::ObjectSchema& scenario_schema() {
  static const scenario::ObjectSchema schema = schema_of(builtin_pipelines());
  return schema;
}

scenario::ScenarioDocument load_scenario(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return scenario::ScenarioDocument::load(file, overrides, &scenario_schema());
}

scenario::ScenarioDocument load_scenario_text(std::string_view text, const std::filesystem::path& name,
                                              const std::vector<std::string>& overrides) {
  return scenario::ScenarioDocument::parse(text, name, overrides, &scenario_schema());
}

std::vector<std::string> validate_scenario(const scenario::ScenarioDocument& doc, double max_events) {
  RunOptions options;
  options.max_events = max_events;
  return PreparedRun(doc, options).warnings();
}

double estimate_scenario_events(const scenario::ScenarioDocument& doc, double max_events) {
  RunOptions options;
  options.max_events = max_events;
  return PreparedRun(doc, options).estimate().events;
}

Json resolve_defaults(const Json& scenario, const std::filesystem::path& base_dir) {
  const auto doc = scenario::ScenarioDocument::from_json(scenario, base_dir);
  RunOptions options;
  options.max_events = 0.0;  // the budget is judged where the run's own limit is known
  return PreparedRun(doc, options).resolved();
}

Json run_scenario(const scenario::ScenarioDocument& doc, const RunOptions& options) {
  // When the command began (reading included), else now: before the build.
  RunOptions timed = options;
  if (!timed.command_start) timed.command_start = std::chrono::steady_clock::now();
  return PreparedRun(doc, timed).run();
}

PreparedRun::PreparedRun(const scenario::ScenarioDocument& doc, RunOptions options)
    : PreparedRun(BoundScenario::of(doc, options.pipelines), std::move(options)) {}

PreparedRun::PreparedRun(std::shared_ptr<const BoundScenario> bound, RunOptions options)
    : options_(std::move(options)), run_(std::make_unique<Run>()) {
  build(*run_, std::move(bound), options_);
  builds_made_.fetch_add(1, std::memory_order_relaxed);
}

PreparedRun::~PreparedRun() = default;

const std::vector<std::string>& PreparedRun::warnings() const { return run_->recording->book().warnings(); }

const EventEstimate& PreparedRun::estimate() const { return run_->estimate; }

Json PreparedRun::resolved() const { return resolved_scenario(*run_); }

Json PreparedRun::run() {
  if (ran_) throw std::logic_error("a prepared run runs once");
  ran_ = true;
  Run& run = *run_;
  const RunOptions& options = options_;
  const auto command_start = options.command_start.value_or(std::chrono::steady_clock::now());
  // Loops outside the event queue (post-processing, long classifications)
  // answer the same stop request as the kernel does.
  const des::ScopedStopFlag stop_flag(options.stop);
  run.files.prepare();
  // Written as it is produced: memory does not grow with the run's length.
  if (run.files.enabled()) run.timeline.stream_to(run.files);
  if (run.files.enabled() && options.write_presentmon)
    run.app_frames.log_presentmon(run.files, run.bound->doc().resolved()["pipeline"].value("type", std::string("latsim")));
  // Per-event timing costs two clock reads per event: only when asked.
  run.sim.set_profiling(options.profile);
  run.sim.watch_stop_flag(options.stop);
  if (options.progress)
    run.sim.watch_progress(kEventsPerProgress, [&run, &options] {
      options.progress(RunProgress{run.sim.now(), run.duration, run.sim.events_executed()});
    });
  const auto t0 = std::chrono::steady_clock::now();
  simulate(run);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  try {
    // As text only for a run that writes no figures.json (which is made from the JSON tree).
    RunFigures figures = figures_of(run, options.figures_text != nullptr && !run.files.enabled());
    Json summary = write_results(run, options, std::move(figures), wall_s, command_start);
    if (options.tables) keep_tables(run, *options.tables);
    return summary;
  } catch (const des::StopRequested&) {
    // The run's files are still staged: RunFiles removes them.
    throw RunInterrupted("while computing and writing its figures", run.duration);
  }
}

uint64_t builds_made() { return builds_made_.load(std::memory_order_relaxed); }

}  // namespace latsim::run
