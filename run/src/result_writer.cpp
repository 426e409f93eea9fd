#include "latsim/run/result_writer.hpp"

#include <sys/resource.h>

#include <cstdio>
#include <string>

namespace latsim::run {

using namespace results;
using Json = nlohmann::json;

namespace {

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

// Simulated seconds for a message, as a reader writes them ("2 s", "0.0166667 s").
std::string format_seconds(des::Time t) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g s", t.to_seconds());
  return buf;
}

// Legal input whose run says little or nothing: the warnings channel tells
// (stderr and summary.json "warnings") instead of an exit 0 in silence.
void warn_about_outcome(Run& run, const RunFigures& figures) {
  FigureBook& rec = run.recording->book();
  const std::string span = format_seconds(run.duration);
  // (A run that shows no image at all is warned of by the recorder.)
  const char* const kMtp = "motion_to_photon_ms";
  int64_t mtp_count = 0;
  if (figures.tree) mtp_count = figures.tree->top(kMtp).count.value_or(0);
  else if (figures.json.contains(kMtp)) mtp_count = figures.json[kMtp].value("count", int64_t{0});
  if (mtp_count == 0)
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

// JSON for a result file: text that is not UTF-8 (a file name from the
// command line) is replaced rather than stopping the run at its very end.
std::string dump(const Json& j, bool compact) {
  return j.dump(compact ? -1 : 2, ' ', false, Json::error_handler_t::replace) + "\n";
}

// The resolved scenario with the defaults that are not single values: the
// probe points used when the scenario names none (the ring around the start).
Json resolved_with_defaults(const Run& run) {
  Json resolved = resolved_scenario(run);
  if (!resolved.contains("probes")) {
    Json points = Json::array();
    for (const glm::dvec3& p : probes_of(run).points_m) points.push_back({p.x, p.y, p.z});
    resolved["probes"] = {{"points_m", std::move(points)}};
  }
  return resolved;
}

}  // namespace

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

RunFigures figures_of(Run& run, bool as_text) {
  RunRecording& rec = *run.recording;
  run.pipeline->finish(*run.ctx);
  run.app_frames.finish(rec.book().writer("application frames"), run.duration);
  if (run.frames) run.frames->finish();
  rec.finish(totals_of(run));
  RunFigures figures;
  if (as_text) figures.tree = rec.book().figure_tree();
  if (!figures.tree) figures.json = rec.book().figures();
  warn_about_outcome(run, figures);
  return figures;
}

Json write_results(Run& run, const RunOptions& options, RunFigures figures,
                   double wall_s, std::chrono::steady_clock::time_point command_start) {
  Json models = Json::object(), events_per_model = Json::object();
  for (const auto& m : run.sim.model_stats()) {
    models[m.model] = {{"events", m.events}};
    if (options.profile) models[m.model]["wall_s"] = m.wall_s;
    events_per_model[m.model] = m.events;
  }
  // figures.json holds only what the scenario and seed determine: byte-identical
  // across runs. summary.json adds wall time, memory and the command line: the
  // same object, once figures.json is written from it (no copy of the figures).
  const FigureBook& book = run.recording->book();
  std::vector<std::string> headline = figures.tree ? book.headline(*figures.tree) : book.headline(figures.json);
  if (figures.tree && options.figures_text) figures.tree->write(*options.figures_text);
  Json summary{{"latsim", {{"version", latsim_version()}, {"git_revision", latsim_git_revision()}}},
               {"seed", run.seed},
               {"replication", options.replication},
               {"scenario", resolved_with_defaults(run)},
               {"figures", std::move(figures.json)},
               {"headline", std::move(headline)},
               {"warnings", run.recording->book().warnings()},
               {"events", run.sim.events_executed()},
               {"events_per_model", std::move(events_per_model)},
               {"fingerprint", hex64(run.sim.fingerprint())}};
  RunFiles& files = run.files;
  if (files.enabled()) {
    run.timeline.finish(files);
    run.app_frames.finish_log(files);
    if (options.write_ledger) run.recording->ledger().write(files);
    if (options.write_samples) run.recording->sample_log().write(files);
    files.write_text("figures.json", dump(summary, options.compact_json));
  }
  summary["command_line"] = options.command_line;
  summary["exit_status"] = 0;
  summary["models"] = std::move(models);
  if (!run.recording->book().captures().empty()) summary["captures"] = run.recording->book().captures();
  summary["events_estimate"] = run.estimate.to_json();
  summary["wall_s"] = wall_s;
  if (run.timeline.size() > 0) summary["timeline_entries"] = run.timeline.size();
  // The whole command and the process's peak, taken after the analytic
  // figures and every other result file: wall_s is the simulation loop alone.
  summary["command_wall_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - command_start).count();
  summary["peak_rss_mb"] = peak_rss_mb();
  // Written last: a run directory is complete exactly when summary.json exists.
  if (files.enabled()) {
    files.write_text("summary.json", dump(summary, options.compact_json));
    files.commit("summary.json");
  }
  return summary;
}

}  // namespace latsim::run
