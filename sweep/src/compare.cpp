#include "latsim/sweep/compare.hpp"

#include <algorithm>
#include <cstdio>

#include "compare_rows.hpp"
#include "latsim/capture/presentmon.hpp"
#include "latsim/capture/runtime_stats.hpp"

namespace latsim::sweep {

namespace {

std::string process_text(const capture::PresentMonProcess& p) {
  std::string t = p.source.string();
  if (!p.application.empty() || p.process_id) {
    t.append(" (").append(p.application);
    if (p.process_id) t.append(p.application.empty() ? "" : " ").append(std::to_string(*p.process_id));
    t.append(")");
  }
  return t.append(", ").append(std::to_string(p.frames.size())).append(" frames");
}

std::string hz(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f Hz", v);
  return buf;
}

// The run side: a run directory, or a PresentMon CSV (a run's presentmon.csv, another capture).
RunSide run_side(const std::filesystem::path& run) {
  std::error_code ec;
  if (std::filesystem::is_directory(run, ec)) {
    if (!std::filesystem::is_regular_file(run / "figures.json", ec))
      throw CompareError(run.string() + ": a directory without figures.json: not a run's output");
    return read_run(run);
  }
  RunSide side;
  side.dir = run.parent_path();
  side.frames = capture::read_presentmon(run, {});
  return side;
}

}  // namespace

const char* standing_name(Standing s) {
  switch (s) {
    case Standing::predicted: return "predicted";
    case Standing::converted: return "converted";
    case Standing::derived: return "derived";
    case Standing::replayed: return "replayed";
    case Standing::input: return "input";
    case Standing::differs: return "differs";
    case Standing::no_counterpart: return "no counterpart";
  }
  return "";
}

Comparison compare_capture(const CompareRequest& q) {
  Comparison out;
  const RunSide run = run_side(q.run);
  out.run_text = run.pipeline.empty() ? (run.frames ? process_text(*run.frames) : q.run.string())
                                      : q.run.string() + " (" + run.pipeline + ", " +
                                            (run.frames ? std::to_string(run.frames->frames.size()) : std::string("no")) +
                                            " frames in presentmon.csv)";
  const capture::Generation g = capture::file_generation(q.capture);
  if (capture::is_presentmon(g)) {
    if (!run.frames) throw CompareError(q.run.string() + ": the run wrote no presentmon.csv to compare a PresentMon capture with");
    const capture::PresentMonProcess cap = capture::read_presentmon(q.capture, q.select);
    out.capture_text = process_text(cap);
    const bool timed = std::any_of(cap.frames.begin(), cap.frames.end(), [](const capture::PresentMonFrame& f) {
      return f.between_presents_ms || f.in_present_ms || f.cpu_busy_ms || f.gpu_busy_ms || f.gpu_time_ms ||
             f.until_displayed_ms || f.between_display_change_ms;
    });
    if (!timed)
      out.warnings.push_back(process_text(cap) + " and not one timing value (every cell NA): only the share of "
                             "frames never displayed is compared");
    if (const auto period = capture::refresh_period_ms(q.capture))
      out.notes.push_back("the capture's display refreshed at " + hz(1000.0 / *period) +
                          (run.refresh_hz > 0 ? "; the run's at " + hz(run.refresh_hz) : std::string()));
    presentmon_rows(cap, run, q, out);
  } else if (g == capture::Generation::ovr_metrics || g == capture::Generation::vrapi || g == capture::Generation::steamvr) {
    if (run.pipeline.empty())
      throw CompareError(q.run.string() + ": a runtime's statistics are compared with a run directory, not a file");
    const capture::RuntimeStats cap = capture::read_runtime_stats(q.capture);
    out.capture_text = q.capture.string() + " (" + capture::generation_name(g) + ", " + std::to_string(cap.rows_read) +
                       (cap.per_frame ? " frames" : " rows, " + std::to_string(cap.partial_rows) + " of them partial seconds left out") + ")";
    if (std::all_of(cap.series.begin(), cap.series.end(), [](const auto& kv) { return kv.second.values.empty(); }))
      out.warnings.push_back(q.capture.string() + ": " + std::to_string(cap.rows_read) +
                             " rows and not one value of a statistic (every cell not available): nothing is compared");
    runtime_rows(cap, run, q, out);
  } else {
    throw CompareError(q.capture.string() + ": neither a PresentMon capture nor a runtime's statistics (OVR Metrics "
                       "Tool CSV, VrApi log, SteamVR frame timing CSV)");
  }
  for (const RunSide::Replayed& x : run.replayed)
    out.notes.push_back("the run replays " + x.column + " of " + x.file.string() +
                        (x.application.empty() ? std::string() : " (" + x.application + ")"));
  return out;
}

}  // namespace latsim::sweep
