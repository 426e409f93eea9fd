#include "latsim/pipelines/runner.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "latsim/des/simulator.hpp"
#include "latsim/display/config.hpp"
#include "latsim/pipelines/frame_capture.hpp"
#include "latsim/pipelines/latency_recorder.hpp"
#include "latsim/pipelines/timeline.hpp"
#include "latsim/pipelines/tracker_host.hpp"
#include "latsim/tracker/config.hpp"

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

Json distribution_json(const des::Distribution& d) {
  const auto s = d.summary();
  Json j{{"count", s.count}, {"mean", s.mean}, {"stddev", s.stddev}, {"min", s.min}, {"p50", s.p50},
         {"p90", s.p90},     {"p99", s.p99},   {"p999", s.p999},     {"max", s.max}};
  Json h = Json::array();
  if (s.count > 0)
    for (const auto& [edge, count] : d.plot_histogram(50)) h.push_back({edge, count});
  j["histogram"] = h;
  return j;
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

/// Everything one run builds from its scenario.
struct Run {
  des::Simulator sim;
  std::unique_ptr<tracker::MotionSource> motion;
  std::unique_ptr<tracker::Tracker> tracker;
  std::unique_ptr<tracker::Transport> transport;
  std::unique_ptr<TrackerHost> host;
  display::DisplayConfig display_config;
  std::unique_ptr<display::Display> display;
  std::unique_ptr<LatencyRecorder> recorder;
  std::unique_ptr<FrameCapture> frames;  // only when the scenario asks for frames
  Timeline timeline;
  std::unique_ptr<Pipeline> pipeline;
  std::unique_ptr<RunContext> ctx;
  uint64_t seed = 1;
  des::Time duration;
  bool keep_timeline = true;
  int64_t timeline_max_entries = 200000;
};

// Builds every model and lets the pipeline schedule its first events; reads
// every key it knows, so unknown keys can be reported before anything runs.
void build(Run& run, const scenario::ScenarioDocument& doc, const RunOptions& options) {
  const scenario::ConfigNode root = doc.root();
  root.string("description", "");
  const double duration_s = root.positive("duration_s", 10.0);
  if (duration_s > 1e6) root.fail("duration_s", "must be at most 1e6 s (int64 picoseconds cover about 9.2e6 s)");
  run.duration = des::Time::from_seconds(duration_s);
  const int64_t seed = root.integer("seed", 1, 0, INT64_MAX);
  run.seed = options.seed ? *options.seed : static_cast<uint64_t>(seed);

  run.motion = tracker::make_motion(root.child("motion"));
  const tracker::TrackerParams tp = tracker::parse_tracker(root.child("tracker"));
  run.tracker = std::make_unique<tracker::Tracker>(tp, *run.motion,
                                                   des::RandomStream(run.seed, "tracker", options.replication));
  if (auto t = root.optional_child("transport")) run.transport = tracker::make_transport(*t);
  else run.transport = std::make_unique<tracker::DirectLink>();
  run.host = std::make_unique<TrackerHost>(run.sim, *run.tracker, *run.transport);

  bool stereo = false;
  double ipd_m = 0.064;
  if (auto h = root.optional_child("host")) {
    stereo = h->boolean("stereo", false);
    ipd_m = h->number_in("ipd_m", 0.064, 0.0, 1.0);
  }
  run.display_config = display::parse_display(root.child("display"));
  run.display = std::make_unique<display::Display>(run.sim, display::RasterTiming(run.display_config.raster),
                                                   stereo ? 2 : 1, run.display_config.fidelity,
                                                   run.display_config.pixel_stride);

  ProbeSet probes = default_probes(run.motion->pose_at(des::Time::zero()), run.display_config.hfov_deg);
  bool keep_samples = false;
  if (auto out = root.optional_child("output")) {
    keep_samples = out->boolean("keep_samples", false);
    run.keep_timeline = out->boolean("timeline", true);
    run.timeline_max_entries = out->integer("timeline_max_entries", 200000, 0, int64_t{1} << 40);
  }
  if (auto pr = root.optional_child("probes")) {
    probes.points_m.clear();
    for (const auto& row : pr->number_rows("points_m")) {
      if (row.size() != 3) pr->fail("points_m", "each probe point needs three coordinates [x, y, z]");
      probes.points_m.emplace_back(row[0], row[1], row[2]);
    }
  }
  run.recorder = std::make_unique<LatencyRecorder>(run.sim, *run.motion, *run.host, run.display->timing(),
                                                   std::move(probes), ipd_m, stereo, keep_samples);
  run.recorder->enable_ledger(options.write_ledger);
  run.recorder->enable_sample_log(options.write_samples);
  run.display->add_listener(run.recorder.get());
  if (auto fr = root.optional_child("frames")) {
    run.frames = make_frame_capture(*fr, root, FrameCaptureInputs{*run.recorder, *run.host, *run.motion,
                                                                  run.display->timing(), run.display_config.hfov_deg,
                                                                  ipd_m, stereo, options.out_dir});
    if (run.frames) run.display->add_listener(run.frames.get());
  }
  LatencyRecorder* rec = run.recorder.get();
  run.host->on_measured([rec](const tracker::TrackerSample& s, des::Time delivered) {
    rec->add("tracker_to_host_ms", (delivered - s.measured_at).to_ms());
  });

  const scenario::ConfigNode pipeline_node = root.child("pipeline");
  const PipelineRegistry registry = builtin_pipelines();
  std::string names;
  for (const auto& n : registry.names()) names += (names.empty() ? "" : ", ") + n;
  const std::string type = pipeline_node.string("type");
  run.pipeline = registry.create(type);
  if (!run.pipeline) pipeline_node.fail("type", "unknown pipeline \"" + type + "\"; known: " + names);

  run.ctx = std::unique_ptr<RunContext>(new RunContext{run.sim, root, pipeline_node, run.seed, options.replication,
                                                       run.duration, *run.motion, *run.host, *run.display,
                                                       *run.recorder, ipd_m, stereo,
                                                       run.keep_timeline ? &run.timeline : nullptr, run.frames.get(),
                                                       options.out_dir});
  run.timeline.set_max_entries(static_cast<size_t>(run.timeline_max_entries));
  run.pipeline->start(*run.ctx);
  doc.check_unknown_keys();
}

Json figures_of(Run& run) {
  Json f = Json::object();
  for (const auto& [name, d] : run.recorder->distributions()) f[name] = distribution_json(d);
  const double duration_s = run.duration.to_seconds();
  const int64_t shown = run.recorder->counter("images_shown");
  f["frame_rate_hz"] = static_cast<double>(shown) / run.display->eyes() / duration_s;
  f["fields"] = run.display->fields_shown();
  f["missed_refreshes"] = 0;
  for (const auto& [name, v] : run.recorder->counters()) f["counts"][name] = v;
  f["tracker_samples"] = run.host->samples_measured();
  run.pipeline->finish(*run.ctx, f);
  if (run.frames) run.frames->finish(f);
  return f;
}

std::string csv_of_ledger(const std::vector<Json>& ledger) {
  std::ostringstream out;
  const char* cols[] = {"frame",        "eye",      "field",         "sample",          "measured_ps",
                        "host_received_ps", "render_start_ps", "render_end_ps", "swap_ps", "scanout_start_ps",
                        "scanout_end_ps"};
  for (size_t i = 0; i < std::size(cols); ++i) out << (i ? "," : "") << cols[i];
  out << '\n';
  for (const auto& row : ledger) {
    for (size_t i = 0; i < std::size(cols); ++i) out << (i ? "," : "") << row[cols[i]].get<int64_t>();
    out << '\n';
  }
  return out.str();
}

}  // namespace

std::string latsim_version() { return LATSIM_VERSION; }
std::string latsim_git_revision() { return LATSIM_GIT_REVISION; }

void write_file_atomically(const std::filesystem::path& file, const std::string& text) {
  const std::filesystem::path tmp = file.string() + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    if (!out) throw std::runtime_error("error writing " + tmp.string());
  }
  std::filesystem::rename(tmp, file);
}

void validate_scenario(const scenario::ScenarioDocument& doc) {
  Run run;
  build(run, doc, RunOptions{});
}

Json run_scenario(const scenario::ScenarioDocument& doc, const RunOptions& options) {
  Run run;
  build(run, doc, options);
  // The scenario is valid: from here on pipelines may write files of their own.
  if (!options.out_dir.empty()) std::filesystem::create_directories(options.out_dir);
  run.sim.set_profiling(true);
  const auto t0 = std::chrono::steady_clock::now();
  run.host->start(run.duration);
  run.display->start(run.duration);
  run.sim.run_until(run.duration);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Json figures = figures_of(run);

  Json models = Json::object(), events_per_model = Json::object();
  for (const auto& m : run.sim.model_stats()) {
    models[m.model] = {{"events", m.events}, {"wall_s", m.wall_s}};
    events_per_model[m.model] = m.events;
  }
  // figures.json holds only what the scenario and seed determine: byte-identical
  // across runs. summary.json adds wall time, memory and the command line.
  Json deterministic{{"latsim", {{"version", latsim_version()}, {"git_revision", latsim_git_revision()}}},
                     {"seed", run.seed},
                     {"replication", options.replication},
                     {"scenario", doc.resolved()},
                     {"figures", figures},
                     {"events", run.sim.events_executed()},
                     {"events_per_model", events_per_model},
                     {"fingerprint", hex64(run.sim.fingerprint())}};
  Json summary = deterministic;
  summary["command_line"] = options.command_line;
  summary["exit_status"] = 0;
  summary["models"] = models;
  summary["wall_s"] = wall_s;
  summary["peak_rss_mb"] = peak_rss_mb();
  if (!run.timeline.entries().empty()) summary["timeline_entries"] = run.timeline.entries().size();

  if (!options.out_dir.empty()) {
    std::filesystem::create_directories(options.out_dir);
    if (!run.timeline.entries().empty()) {
      run.timeline.write_csv(options.out_dir / "timeline.csv");
      run.timeline.write_trace_json(options.out_dir / "timeline.json");
    }
    if (options.write_ledger) write_file_atomically(options.out_dir / "frames.csv", csv_of_ledger(run.recorder->ledger()));
    if (options.write_samples) {
      std::ostringstream s;
      s << "t_ms,name,value\n";
      char buf[96];
      for (const auto& x : run.recorder->sample_log()) {
        std::snprintf(buf, sizeof buf, "%.6f,%s,%.9g\n", x.t_ms, x.name.c_str(), x.value);
        s << buf;
      }
      write_file_atomically(options.out_dir / "samples.csv", s.str());
    }
    write_file_atomically(options.out_dir / "figures.json", deterministic.dump(2) + "\n");
    // Written last: a run directory is complete exactly when summary.json exists.
    write_file_atomically(options.out_dir / "summary.json", summary.dump(2) + "\n");
  }
  return summary;
}

}  // namespace latsim::pipelines
