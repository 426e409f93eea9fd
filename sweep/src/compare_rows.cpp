// The quantities latsim compare sets side by side: those of a PresentMon
// capture, or of a runtime's statistics, against a run (docs/figures.md).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "compare_rows.hpp"

namespace latsim::sweep {

namespace {

std::string fmt(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

CompareSide side(std::string column, std::vector<double> values, bool total_only) {
  CompareSide s{std::move(column), std::move(values), total_only, {}};
  s.stats = capture::sample_stats(s.values);
  return s;
}

template <class F>
std::vector<double> frames_of(const capture::PresentMonProcess& p, F get) {
  std::vector<double> out;
  for (const capture::PresentMonFrame& f : p.frames)
    if (f.application_frame)
      if (const std::optional<double> v = get(f)) out.push_back(*v);
  return out;
}

// Display-change intervals from the flips a run reports (its MsUntilScanout).
std::vector<double> scanout_changes(const capture::PresentMonProcess& run, const std::vector<std::optional<double>>& flip) {
  std::vector<double> out;
  std::optional<double> last;
  for (size_t j = 0; j < run.frames.size(); ++j) {
    if (!flip[j]) continue;
    if (last) out.push_back(*flip[j] - *last);
    last = flip[j];
  }
  return out;
}

CompareSide side(std::string column, std::vector<double> values) { return side(std::move(column), std::move(values), false); }

/// The verdict of one row: samples by KS distance, a total by its distance
/// from the capture's mean (within mean_tolerance of it, or `floor`).
void judge(CompareRow& r, const CompareRequest& q, double floor, const std::string& unit) {
  const bool in_verdict =
      r.standing == Standing::predicted || r.standing == Standing::converted || r.standing == Standing::derived;
  const auto& c = r.capture.stats;
  const auto& u = r.run.stats;
  if (!r.capture.total_only && !r.run.total_only) r.ks = capture::ks_distance(r.capture.values, r.run.values);
  const std::string means = c.mean && u.mean ? " (capture mean " + fmt(*c.mean) + unit + ", run " + fmt(*u.mean) + unit + ")" : "";
  switch (r.standing) {
    case Standing::replayed:
      r.verdict = "replayed: the run plays the capture's own values back, so agreement proves nothing; left out" + means;
      return;
    case Standing::input:
      r.verdict = "set by the scenario, not predicted; left out" + means;
      return;
    case Standing::differs:
      r.verdict = "defined differently and not convertible (" + r.note + "); left out" + means;
      return;
    case Standing::no_counterpart:
      r.verdict = "no counterpart: " + r.note + "; left out";
      return;
    default: break;
  }
  if (!in_verdict || !c.mean || !u.mean) {
    r.verdict = "no values on " + std::string(!c.mean ? "the capture's" : "the run's") + " side; left out";
    r.standing = Standing::no_counterpart;
    return;
  }
  if (r.ks) {
    r.agrees = *r.ks <= q.ks_threshold;
    r.verdict = std::string(*r.agrees ? "agrees" : "differs") + ": KS " + fmt(*r.ks) + (*r.agrees ? " <= " : " > ") +
                fmt(q.ks_threshold) + means;
  } else {
    const double tolerance = std::max(q.mean_tolerance * std::fabs(*c.mean), floor);
    r.agrees = std::fabs(*u.mean - *c.mean) <= tolerance;
    r.verdict = std::string(*r.agrees ? "agrees" : "differs") + ": the run's " + fmt(*u.mean) + unit + " is " +
                (*r.agrees ? "within " : "more than ") + fmt(tolerance) + unit + " of the capture's mean " +
                fmt(*c.mean) + unit;
  }
  if (r.standing == Standing::converted || r.standing == Standing::derived) r.verdict += "; " + r.note;
}

CompareRow row(std::string key, std::string label, CompareSide capture, CompareSide run, Standing standing,
               std::string note) {
  CompareRow r;
  r.key = std::move(key);
  r.label = std::move(label);
  r.capture = std::move(capture);
  r.run = std::move(run);
  r.standing = standing;
  r.note = std::move(note);
  return r;
}

CompareRow row(std::string key, std::string label, CompareSide capture, CompareSide run, Standing standing) {
  return row(std::move(key), std::move(label), std::move(capture), std::move(run), standing, {});
}

}  // namespace

CompareSide compare_side(std::string column, std::vector<double> values, bool total_only) {
  return side(std::move(column), std::move(values), total_only);
}
CompareRow compare_row(std::string key, std::string label, CompareSide capture, CompareSide run, Standing standing,
                       std::string note) {
  return row(std::move(key), std::move(label), std::move(capture), std::move(run), standing, std::move(note));
}
void compare_judge(CompareRow& r, const CompareRequest& q, double floor, const std::string& unit) {
  judge(r, q, floor, unit);
}

// PresentMon capture against a run's presentmon.csv (or another capture).
void presentmon_rows(const capture::PresentMonProcess& cap, const RunSide& run, const CompareRequest& q,
                     Comparison& out) {
  const capture::PresentMonProcess& rf = *run.frames;
  const bool from_run = !run.pipeline.empty();
  auto replayed = [&](const char* quantity) {
    return from_run && replays(run, q.capture, quantity, cap.application, cap.process_id);
  };
  const bool busy_replayed = replayed("cpu_busy"), wait_replayed = replayed("cpu_wait");
  const std::string ms = " ms";

  // Frame interval.
  {
    CompareRow r = row("frame_interval", "frame interval (ms)",
                       side("MsBetweenPresents", frames_of(cap, [](auto& f) { return f.between_presents_ms; })),
                       side("MsBetweenPresents", frames_of(rf, [](auto& f) { return f.between_presents_ms; })),
                       busy_replayed && wait_replayed ? Standing::derived : Standing::predicted);
    if (busy_replayed && wait_replayed)
      r.note = "the run's intervals are the capture's CPU busy and CPU wait replayed plus the blocking its own present "
               "path adds: agreement says that path blocks no more than the capture's did";
    judge(r, q, 0.5, ms);
    out.rows.push_back(std::move(r));
  }
  // CPU busy: PresentMon's holds the application's own waiting.
  {
    const bool replay_pipeline = run.pipeline == "present_replay";
    Standing st = busy_replayed ? Standing::replayed : (replay_pipeline || !from_run) ? Standing::predicted : Standing::differs;
    CompareRow r = row("cpu_busy", "CPU busy (ms)", side("MsCPUBusy", frames_of(cap, [](auto& f) { return f.cpu_busy_ms; })),
                       side("MsCPUBusy", frames_of(rf, [](auto& f) { return f.cpu_busy_ms; })), st,
                       "PresentMon's CPU busy runs from the previous Present's return to this one's call, the "
                       "application's own waiting included; latsim's " + run.pipeline + " reports the work of its CPU "
                       "stages alone");
    judge(r, q, 0.5, ms);
    out.rows.push_back(std::move(r));
  }
  // CPU wait: the time in Present.
  {
    std::vector<double> run_wait = frames_of(rf, [](auto& f) { return f.in_present_ms; });
    const Standing st = run_wait.empty() ? Standing::no_counterpart : wait_replayed ? Standing::derived : Standing::predicted;
    CompareRow r = row("cpu_wait", "CPU wait: time in Present (ms)",
                       side("MsCPUWait", frames_of(cap, [](auto& f) { return f.in_present_ms; })),
                       side("MsCPUWait", std::move(run_wait)), st,
                       st == Standing::derived ? "the capture's time in Present replayed, plus the run's own blocking"
                                               : "the run's present takes no time (its pipeline models no Present call)");
    judge(r, q, 0.5, ms);
    out.rows.push_back(std::move(r));
  }
  // GPU busy.
  {
    CompareRow r = row("gpu_busy", "GPU busy (ms)", side("MsGPUBusy", frames_of(cap, [](auto& f) { return f.gpu_busy_ms; })),
                       side("MsGPUBusy", frames_of(rf, [](auto& f) { return f.gpu_busy_ms; })),
                       replayed("gpu_busy") ? Standing::replayed : Standing::predicted);
    judge(r, q, 0.5, ms);
    out.rows.push_back(std::move(r));
  }
  // Present to display: PresentMon's is the flip, latsim's MsUntilDisplayed first light.
  {
    std::vector<std::optional<double>> flip(rf.frames.size());
    std::vector<double> until;
    for (size_t j = 0; j < rf.frames.size(); ++j) {
      const capture::PresentMonFrame& f = rf.frames[j];
      const std::optional<double> v = from_run ? f.until_scanout_ms : f.until_displayed_ms;
      if (!v) continue;
      until.push_back(*v);
      if (f.present_time_s) flip[j] = *f.present_time_s * 1000.0 + *v;
    }
    const bool have = !until.empty();
    CompareRow r = row("until_displayed", "present to display (ms)",
                       side("MsUntilDisplayed", frames_of(cap, [](auto& f) { return f.until_displayed_ms; })),
                       side(from_run ? "MsUntilScanout" : "MsUntilDisplayed", until),
                       !from_run ? Standing::predicted : have ? Standing::converted : Standing::differs,
                       from_run ? "PresentMon's display time is the flip that first shows the frame; latsim's "
                                  "MsUntilDisplayed is its first light, so the run's MsUntilScanout (the same flip) is compared"
                                : "");
    if (from_run && !have)
      r.note = "PresentMon's display time is the flip; the run reports only first light (no MsUntilScanout: its "
               "frames reach the screen through a compositor's own images)";
    judge(r, q, 0.5, ms);
    out.rows.push_back(std::move(r));
    // Display changes are whole refreshes apart on a display that flips at
    // its retraces; the capture times them to its clock's jitter, the run
    // exactly: both are compared in refreshes of their own display.
    const std::optional<double> cap_period = capture::refresh_period_ms(q.capture);
    const double run_period = run.refresh_hz > 0.0 ? 1000.0 / run.refresh_hz : cap_period.value_or(0.0);
    auto in_refreshes = [](std::vector<double> v, std::optional<double> period) {
      if (period && *period > 0.0)
        for (double& x : v) x = std::round(x / *period);
      return v;
    };
    std::vector<double> cap_changes = frames_of(cap, [](auto& f) { return f.between_display_change_ms; });
    std::vector<double> run_changes =
        from_run ? scanout_changes(rf, flip) : frames_of(rf, [](auto& f) { return f.between_display_change_ms; });
    const bool periods = cap_period.has_value() && run_period > 0.0;
    CompareRow c = row("display_change", periods ? "display change interval (refreshes)" : "display change interval (ms)",
                       side("MsBetweenDisplayChange", in_refreshes(std::move(cap_changes), cap_period)),
                       side(from_run ? "between flips (MsUntilScanout)" : "MsBetweenDisplayChange",
                            in_refreshes(std::move(run_changes), periods ? std::optional(run_period) : std::nullopt)),
                       !from_run ? Standing::predicted : have ? Standing::converted : Standing::differs,
                       periods ? "the interval between the flips of successive displayed frames, in refreshes of "
                                 "each side's display (the capture's timed to its clock's jitter)"
                               : "the interval between the flips of successive displayed frames");
    judge(c, q, periods ? 0.05 : 0.5, periods ? "" : ms);
    out.rows.push_back(std::move(c));
  }
  // Frames never displayed, as 0/1 per frame: the KS distance is the difference of the shares.
  {
    auto dropped = [](const capture::PresentMonProcess& p) {
      std::vector<double> v;
      for (const capture::PresentMonFrame& f : p.frames)
        if (f.application_frame) v.push_back(f.displayed ? 0.0 : 1.0);
      return v;
    };
    CompareRow r = row("dropped", "frames never displayed (share)", side("Dropped", dropped(cap)),
                       side("Dropped", dropped(rf)), Standing::predicted);
    judge(r, q, 0.05, "");
    out.rows.push_back(std::move(r));
  }
}

}  // namespace latsim::sweep
