#include "latsim/pipelines/runner.hpp"

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "latsim/des/simulator.hpp"
#include "latsim/params/shared.hpp"
#include "latsim/pipelines/frame_capture.hpp"
#include "latsim/pipelines/latency_recorder.hpp"
#include "latsim/pipelines/run_clocks.hpp"
#include "latsim/pipelines/smear_recorder.hpp"
#include "latsim/pipelines/timeline.hpp"
#include "latsim/pipelines/tracker_host.hpp"
#include "latsim/tracker/params.hpp"

namespace latsim::pipelines {

namespace {

using Json = nlohmann::json;
constexpr double kPi = 3.14159265358979323846;

/// A ring of points 2 m around the start position, every 15 degrees of yaw at
/// three heights, so that some are in view whatever the head does.
ProbeSet default_probes(const tracker::Pose& start, double hfov_deg) {
  ProbeSet p;
  p.hfov_deg = hfov_deg;
  for (int i = 0; i < 24; ++i)
    for (int k = -1; k <= 1; ++k) {
      const double yaw = i * 15.0 * kPi / 180.0, pitch = k * 15.0 * kPi / 180.0;
      const glm::dvec3 dir(-std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch));
      p.points_m.push_back(start.position_m + 2.0 * dir);
    }
  return p;
}

double peak_rss_mb() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_maxrss) / 1024.0;
}

std::string hex64(uint64_t v) {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

/// Declares (reading mode: reads) the whole scenario: the shared sections,
/// then /pipeline through the declaration of the pipeline its "type" names.
PipelineFactory bind_scenario(scenario::Section& root, params::SharedParams& shared, const PipelineRegistry& registry) {
  params::bind(root, shared);
  PipelineFactory factory;
  std::vector<scenario::ModeDecl> modes;
  for (const auto& named : registry.entries()) {
    // A reference, not a structured binding: clang before 16 cannot capture bindings in a lambda.
    const auto& entry = named.second;
    modes.push_back(
        {named.first, entry.doc, [&factory, &shared, &entry](scenario::Section& p) { factory = entry.bind(p, shared); }});
  }
  int unused = 0;
  root.object("pipeline", unused,
              [&modes](scenario::Section& p, int&) {
                p.doc("The display strategy: which pose each image is computed from, when it is ready, and when it "
                      "goes into a front buffer. `type` selects the pipeline; each reads its own keys.");
                p.modes("type", "", modes, {.doc = "which pipeline"});
              },
              {.required = true, .doc = "the display strategy"});
  return factory;
}

/// The declaration of every key of a scenario whose pipelines are `registry`'s.
scenario::ObjectSchema schema_of(const PipelineRegistry& registry) {
  scenario::ObjectSchema root;
  scenario::Section s(root);
  params::SharedParams shared;
  (void)bind_scenario(s, shared, registry);
  return root;
}

/// Everything one run builds from its scenario.
struct Run {
  des::Simulator sim;
  params::SharedParams shared;
  std::vector<std::string> input_warnings;
  std::unique_ptr<tracker::MotionSource> motion;
  std::unique_ptr<tracker::Tracker> tracker;
  std::unique_ptr<tracker::Transport> transport;
  std::unique_ptr<TrackerHost> host;
  std::unique_ptr<display::Display> display;
  std::unique_ptr<LatencyRecorder> recorder;
  std::unique_ptr<FrameCapture> frames;  // only when the scenario asks for frames
  std::unique_ptr<SmearRecorder> smear;  // only on a display with persistence
  RunFiles files;
  std::unique_ptr<RunClocks> clocks;
  Timeline timeline;
  std::unique_ptr<Pipeline> pipeline;
  std::unique_ptr<RunContext> ctx;
  uint64_t seed = 1;
  des::Time duration;
};

// Every clock of the shared models gets the phase the scenario fixes or one
// drawn for this replication; the display's raster takes the actual period
// (the tracker and the link apply their rate errors themselves).
void resolve_clocks(Run& run, uint64_t replication) {
  params::SharedParams& p = run.shared;
  run.clocks = std::make_unique<RunClocks>(run.seed, replication);
  // A rate error that leaves a period no 64-bit fraction holds is the scenario's problem, at its key.
  auto resolve = [&run](const char* name, const std::string& prefix, des::RationalSeconds period,
                        des::ClockSettings& settings) -> const des::Clock& {
    try {
      return run.clocks->resolve(name, prefix + "phase_ms", period, settings);
    } catch (const std::invalid_argument& e) {
      throw scenario::ScenarioError(prefix + "rate_error_ppm", e.what());
    }
  };
  resolve("tracker", "/tracker/", p.tracker.period, p.tracker.clock);
  tracker::SerialLinkParams& serial = p.transport.serial;
  if (p.transport.type == tracker::TransportParams::Type::Serial && serial.host_mode == tracker::SerialLinkParams::Poll)
    resolve("poll", "/transport/poll_", tracker::exact_period(serial.poll_interval), serial.poll_clock);
  const des::Clock& display = resolve("display", "/display/", p.display.raster.field_period, p.display.clock);
  p.display.raster.field_period = display.period;
}

ProbeSet probes_of(const Run& run) {
  const double hfov_deg = run.shared.display.hfov_deg;
  if (!run.shared.probes) return default_probes(run.motion->pose_at(des::Time::zero()), hfov_deg);
  return ProbeSet{run.shared.probes->points_m, hfov_deg};
}

// Simulated seconds for a message, as a reader writes them ("2 s", "0.0166667 s").
std::string format_seconds(des::Time t) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g s", t.to_seconds());
  return buf;
}

// Builds one part of a run. Building depends on the scenario alone, so
// anything it throws is a problem of the scenario at `pointer`: `validate`
// reports it exactly as `run` does, exit 2, and never a library's raw text.
template <class F>
void built_from(const char* pointer, const char* what, F&& make) {
  try {
    make();
  } catch (const scenario::ScenarioError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw scenario::ScenarioError(pointer, std::string("not enough memory to build the ") + what);
  } catch (const std::exception& e) {
    throw scenario::ScenarioError(pointer, std::string("cannot build the ") + what + ": " + e.what());
  }
}

// Reads every key first, so bad and unknown keys are reported before
// anything is built; then builds every model and lets the pipeline schedule
// its first events.
void build(Run& run, const scenario::ScenarioDocument& doc, const RunOptions& options) {
  const PipelineRegistry builtin = options.pipelines ? PipelineRegistry{} : builtin_pipelines();
  const PipelineRegistry& registry = options.pipelines ? *options.pipelines : builtin;
  PipelineFactory make_pipeline;
  built_from("", "scenario", [&] {
    scenario::Section root(doc.root());
    make_pipeline = bind_scenario(root, run.shared, registry);
    if (options.pipelines) {
      const scenario::ObjectSchema schema = schema_of(registry);
      doc.check_unknown_keys(&schema, &run.input_warnings);
    } else {
      doc.check_unknown_keys(&scenario_schema(), &run.input_warnings);
    }
  });

  run.duration = des::Time::from_seconds(run.shared.duration_s);
  run.seed = options.seed ? *options.seed : static_cast<uint64_t>(run.shared.seed);
  resolve_clocks(run, options.replication);
  const params::SharedParams& p = run.shared;
  built_from("/motion", "head motion", [&] { run.motion = tracker::make_motion(p.motion); });
  built_from("/tracker", "tracker", [&] {
    run.tracker = std::make_unique<tracker::Tracker>(p.tracker, *run.motion,
                                                     des::RandomStream(run.seed, "tracker", options.replication));
  });
  built_from("/transport", "transport", [&] { run.transport = tracker::make_transport(p.transport); });
  Timeline* timeline = p.output.timeline ? &run.timeline : nullptr;
  run.timeline.set_max_entries(static_cast<size_t>(p.output.timeline_max_entries));
  run.host = std::make_unique<TrackerHost>(run.sim, *run.tracker, *run.transport, timeline, p.host.prediction);
  const bool stereo = p.host.stereo;
  built_from("/display", "display", [&] {
    run.display = std::make_unique<display::Display>(run.sim,
                                                     display::RasterTiming(p.display.raster, *p.display.clock.phase),
                                                     stereo ? 2 : 1, p.display.fidelity, p.display.pixel_stride,
                                                     p.display.pixel_events);
  });
  built_from("/probes", "registration probes", [&] {
    run.recorder = std::make_unique<LatencyRecorder>(run.sim, *run.motion, *run.host, run.display->timing(),
                                                     probes_of(run), p.host.ipd_m, stereo, p.output.keep_samples);
  });
  for (const auto& w : run.input_warnings) run.recorder->warn(w);
  run.recorder->enable_prediction(p.host.prediction.has_value());
  if (p.motion_phases) run.recorder->split_by_phase(*p.motion_phases);
  run.recorder->enable_ledger(options.write_ledger);
  run.recorder->enable_sample_log(options.write_samples);
  run.display->add_listener(run.recorder.get());
  if (p.display.persistence) {
    run.display->set_persistence(*p.display.persistence);
    run.recorder->set_persistence(&run.display->persistence());
    run.smear = std::make_unique<SmearRecorder>(*run.recorder, *run.motion);
    run.display->add_listener(run.smear.get());
  }
  run.files = RunFiles(options.out_dir, options.staging_dir);
  if (p.frames && p.frames->enabled) {
    built_from("/frames", "frame capture", [&] {
      run.frames = std::make_unique<FrameCapture>(
          *p.frames, p.scene ? p.scene->geometry : renderer::SceneSpec{},
          FrameCaptureInputs{*run.recorder, *run.host, *run.motion, run.display->timing(), p.display.hfov_deg,
                             p.host.ipd_m, stereo, run.files,
                             p.display.persistence ? &run.display->persistence() : nullptr});
    });
    run.display->add_listener(run.frames.get());
  }
  LatencyRecorder* rec = run.recorder.get();
  rec->set_timeline(timeline);
  const bool line = run.transport->occupancy() > des::Time::zero();
  run.host->on_carried([rec, line](const tracker::TrackerSample& s, const tracker::Carriage& c) {
    rec->record_carried(s, c, line);
  });

  built_from("/pipeline", "pipeline", [&] {
    run.pipeline = make_pipeline();
    run.ctx = std::unique_ptr<RunContext>(new RunContext{
        run.sim, run.seed, options.replication, run.duration, *run.motion, p.tracker, *run.transport, *run.host,
        *run.display, p.display, p.scene ? &*p.scene : nullptr, *run.recorder, run.files, *run.clocks, p.host.ipd_m,
        stereo, timeline, run.frames.get()});
    run.pipeline->start(*run.ctx);
  });
  // The phases used, drawn or fixed, make the resolved scenario reproduce this run.
  for (const auto& [pointer, ms] : run.clocks->phases_ms()) doc.resolve(pointer, ms);
}

RunTotals totals_of(const Run& run) {
  RunTotals t;
  t.duration = run.duration;
  t.fields = run.display->fields_shown();
  t.tracker_samples = run.host->samples_measured();
  t.tracker_period = run.tracker->nominal_time(1) - run.tracker->nominal_time(0);
  t.records_dropped = run.host->records_dropped();
  t.records_waiting = run.host->records_waiting();
  t.line_occupancy = run.transport->occupancy();
  t.buffer_records = run.transport->buffer_records();
  if (const auto* serial = dynamic_cast<const tracker::SerialLink*>(run.transport.get())) {
    const tracker::SerialLinkParams& sp = serial->params();
    if (sp.host_mode == tracker::SerialLinkParams::Interrupt) t.handler_time = serial->handler_time();
    char buf[96];
    std::snprintf(buf, sizeof buf, "%lld-byte records at %g baud", static_cast<long long>(sp.record_bytes), sp.baud);
    t.link_description = buf;
  }
  return t;
}

// Legal input whose run says little or nothing: the warnings channel tells
// (stderr and summary.json "warnings") instead of an exit 0 in silence.
void warn_about_outcome(Run& run, const Json& figures) {
  LatencyRecorder& rec = *run.recorder;
  const std::string span = format_seconds(run.duration);
  // (A run that shows no image at all is warned of by the recorder.)
  const Json* mtp = figures.contains("motion_to_photon_ms") ? &figures["motion_to_photon_ms"] : nullptr;
  if (mtp == nullptr || mtp->value("count", int64_t{0}) == 0)
    rec.warn("no motion-to-photon latency figure: no tracker sample reached a displayed pixel in the " + span +
             " simulated");
  // A sample jittered past the end of the run ends the tracker's chain of samples early.
  const tracker::Tracker& tracker = *run.tracker;
  const int64_t expected =
      tracker.first_index_at_or_after(run.duration) - tracker.first_index_at_or_after(des::Time::zero());
  const int64_t measured = run.host->samples_measured();
  if (tracker.params().jitter > des::Time::zero() && measured < expected)
    rec.warn("tracker jitter of " + format_seconds(tracker.params().jitter) + " dropped " +
             std::to_string(expected - measured) + " of " + std::to_string(expected) +
             " samples (a sample jittered past the end of the run, or reports held in order past it); keep "
             "/tracker/jitter_ms below half the sampling period");
}

Json figures_of(Run& run) {
  LatencyRecorder& rec = *run.recorder;
  run.pipeline->finish(*run.ctx);
  if (run.frames) run.frames->finish();
  rec.finish(totals_of(run));
  Json figures = rec.figures();
  warn_about_outcome(run, figures);
  return figures;
}

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
  } catch (const WriteError&) {
    throw;
  } catch (const std::exception& e) {
    const auto kind = run.sim.failed_kind();
    const std::string name = kind ? run.sim.kind_name(*kind) : std::string("start");
    throw RunFailure(name.substr(0, name.find('.')), run.sim.now(),
                     dynamic_cast<const std::bad_alloc*>(&e) ? std::string("out of memory") : std::string(e.what()));
  }
  if (run.sim.interrupted()) throw RunInterrupted(run.sim.now(), run.duration);
}

// JSON for a result file: text that is not UTF-8 (a file name from the
// command line) is replaced rather than stopping the run at its very end.
std::string dump(const Json& j) { return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n"; }

std::string csv_of_ledger(const std::vector<Json>& ledger) {
  std::ostringstream out;
  const char* cols[] = {"frame",        "eye",      "field",         "sample",          "measured_ps",
                        "host_received_ps", "render_start_ps", "render_end_ps", "predicted_for_ps", "swap_ps",
                        "scanout_start_ps", "scanout_end_ps", "image", "continues_image"};
  for (size_t i = 0; i < std::size(cols); ++i) out << (i ? "," : "") << cols[i];
  out << '\n';
  for (const auto& row : ledger) {
    for (size_t i = 0; i < std::size(cols); ++i) out << (i ? "," : "") << row[cols[i]].get<int64_t>();
    out << '\n';
  }
  return out.str();
}

std::string csv_of_rows(const std::vector<std::string>& columns, const std::vector<std::vector<int64_t>>& rows) {
  std::ostringstream out;
  for (size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
  out << '\n';
  for (const auto& row : rows) {
    for (size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << row[i];
    out << '\n';
  }
  return out.str();
}

std::string csv_of_samples(const std::vector<LatencyRecorder::LoggedSample>& samples) {
  std::ostringstream s;
  s << "t_ms,name,value\n";
  char buf[96];
  for (const auto& x : samples) {
    std::snprintf(buf, sizeof buf, "%.6f,%s,%.9g\n", x.t_ms, x.name.c_str(), x.value);
    s << buf;
  }
  return s.str();
}

}  // namespace

namespace {

// Simulated seconds for a message, as precise as a picosecond needs.
std::string seconds_text(des::Time t) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.12g s", t.to_seconds());
  return buf;
}

}  // namespace

RunFailure::RunFailure(std::string model, des::Time at, const std::string& cause)
    : std::runtime_error("run failed in " + model + " at simulated t = " + seconds_text(at) + ": " + cause),
      model_(std::move(model)),
      at_(at) {}

RunInterrupted::RunInterrupted(des::Time at, des::Time end)
    : std::runtime_error("interrupted at simulated t = " + seconds_text(at) + " of " + seconds_text(end)), at_(at) {}

std::string latsim_version() { return LATSIM_VERSION; }
std::string latsim_git_revision() { return LATSIM_GIT_REVISION; }

const scenario::ObjectSchema& scenario_schema() {
  static const scenario::ObjectSchema schema = schema_of(builtin_pipelines());
  return schema;
}

scenario::ScenarioDocument load_scenario(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return scenario::ScenarioDocument::load(file, overrides, &scenario_schema());
}

std::vector<std::string> validate_scenario(const scenario::ScenarioDocument& doc) {
  Run run;
  build(run, doc, RunOptions{});
  return run.recorder->warnings();
}

// The resolved scenario with the defaults that are not single values: the
// probe points used when the scenario names none (the ring around the start).
static Json resolved_with_defaults(const Run& run, const scenario::ScenarioDocument& doc) {
  Json resolved = doc.resolved();
  if (!resolved.contains("probes")) {
    Json points = Json::array();
    for (const glm::dvec3& p : probes_of(run).points_m) points.push_back({p.x, p.y, p.z});
    resolved["probes"] = {{"points_m", std::move(points)}};
  }
  return resolved;
}

Json run_scenario(const scenario::ScenarioDocument& doc, const RunOptions& options) {
  const auto command_start = options.command_start.value_or(std::chrono::steady_clock::now());
  Run run;
  build(run, doc, options);
  run.files.prepare();
  // Written as it is produced: memory does not grow with the run's length.
  if (run.files.enabled()) run.timeline.stream_to(run.files);
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
  Json figures = figures_of(run);

  Json models = Json::object(), events_per_model = Json::object();
  for (const auto& m : run.sim.model_stats()) {
    models[m.model] = {{"events", m.events}};
    if (options.profile) models[m.model]["wall_s"] = m.wall_s;
    events_per_model[m.model] = m.events;
  }
  // figures.json holds only what the scenario and seed determine: byte-identical
  // across runs. summary.json adds wall time, memory and the command line.
  Json deterministic{{"latsim", {{"version", latsim_version()}, {"git_revision", latsim_git_revision()}}},
                     {"seed", run.seed},
                     {"replication", options.replication},
                     {"scenario", resolved_with_defaults(run, doc)},
                     {"figures", figures},
                     {"warnings", run.recorder->warnings()},
                     {"events", run.sim.events_executed()},
                     {"events_per_model", events_per_model},
                     {"fingerprint", hex64(run.sim.fingerprint())}};
  Json summary = deterministic;
  summary["command_line"] = options.command_line;
  summary["exit_status"] = 0;
  summary["models"] = models;
  summary["wall_s"] = wall_s;
  if (run.timeline.size() > 0) summary["timeline_entries"] = run.timeline.size();

  RunFiles& files = run.files;
  if (files.enabled()) {
    run.timeline.finish(files);
    if (options.write_ledger) {
      const LatencyRecorder& r = *run.recorder;
      files.write_text("frames.csv", csv_of_ledger(r.ledger()));
      files.write_text("fields.csv", csv_of_rows(LatencyRecorder::field_ledger_columns(), r.field_ledger()));
      files.write_text("tracker.csv", csv_of_rows(LatencyRecorder::tracker_ledger_columns(), r.tracker_ledger()));
    }
    if (options.write_samples) files.write_text("samples.csv", csv_of_samples(run.recorder->sample_log()));
    files.write_text("figures.json", dump(deterministic));
  }
  // The whole command and the process's peak, taken after the analytic
  // figures and every other result file: wall_s is the simulation loop alone.
  summary["command_wall_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - command_start).count();
  summary["peak_rss_mb"] = peak_rss_mb();
  // Written last: a run directory is complete exactly when summary.json exists.
  if (files.enabled()) {
    files.write_text("summary.json", dump(summary));
    files.commit("summary.json");
  }
  return summary;
}

}  // namespace latsim::pipelines
