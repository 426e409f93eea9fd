// A runtime's own statistics (OVR Metrics Tool, VrApi, SteamVR frame timing)
// against a run's figures (docs/figures.md, "latsim compare").
#include <cmath>

#include "compare_rows.hpp"

namespace latsim::sweep {

namespace {

std::vector<double> values_of(const capture::RuntimeStats& s, const char* key) {
  const capture::StatSeries* v = s.find(key);
  return v ? v->values : std::vector<double>();
}

// Application frames a whole simulated second, from presentmon.csv's present times.
std::vector<double> frames_per_second(const RunSide& run) {
  std::vector<double> out;
  if (!run.frames || run.seconds < 1.0) return out;
  out.assign(static_cast<size_t>(std::floor(run.seconds)), 0.0);
  for (const capture::PresentMonFrame& f : run.frames->frames)
    if (f.present_time_s && *f.present_time_s >= 0.0) {
      const auto s = static_cast<size_t>(std::floor(*f.present_time_s));
      if (s < out.size()) out[s] += 1.0;
    }
  return out;
}

std::vector<double> one(std::optional<double> v) { return v ? std::vector<double>{*v} : std::vector<double>(); }

std::optional<double> per_second(const RunSide& run, const char* figure) {
  const auto v = run.figure(figure);
  if (!v || run.seconds <= 0.0) return std::nullopt;
  return *v / run.seconds;
}

}  // namespace

void runtime_rows(const capture::RuntimeStats& cap, const RunSide& run, const CompareRequest& q, Comparison& out) {
  auto add = [&](CompareRow r, double floor, const char* unit) {
    compare_judge(r, q, floor, unit);
    out.rows.push_back(std::move(r));
  };
  auto replayed = [&](const char* quantity) { return replays(run, q.capture, quantity, "", std::nullopt); };

  add(compare_row("frame_rate", "application frames a second (Hz)",
                  compare_side("frame_rate_hz", values_of(cap, "frame_rate_hz"), false),
                  compare_side("presentmon.csv rows a simulated second", frames_per_second(run), false),
                  Standing::predicted, ""),
      1.0, " Hz");
  add(compare_row("refresh", "display refresh (Hz)", compare_side("refresh_hz", values_of(cap, "refresh_hz"), false),
                  compare_side("/display/refresh_hz", one(run.refresh_hz > 0 ? std::optional(run.refresh_hz) : std::nullopt), true),
                  Standing::input, ""),
      0.5, " Hz");
  add(compare_row("prediction", "prediction time: pose query to display (ms)",
                  compare_side("prediction_ms", values_of(cap, "prediction_ms"), false),
                  compare_side("query_to_photon_ms (mean)", one(run.figure("query_to_photon_ms", "mean")), true),
                  Standing::predicted,
                  "the runtime's prediction time runs from the application's pose query to the display time it "
                  "predicted; latsim's query_to_photon_ms from the pose query to the photon time it was predicted for"),
      1.0, " ms");
  add(compare_row("stale", "stale refreshes a second (1/s)", compare_side("stale_per_s", values_of(cap, "stale_per_s"), false),
                  compare_side("frames_rewarped / simulated seconds", one(per_second(run, "frames_rewarped")), true),
                  Standing::predicted, ""),
      1.0, " /s");
  add(compare_row("early", "early frames a second (1/s)", compare_side("early_per_s", values_of(cap, "early_per_s"), false),
                  compare_side("-", {}, true), Standing::no_counterpart,
                  "latsim's compositor shows each frame at the first refresh it is ready for, so none is early (a "
                  "runtime counts a frame early when it is done a whole refresh before it is needed, as in its "
                  "extra latency mode)"),
      1.0, " /s");
  add(compare_row("tears", "torn refreshes a second (1/s)", compare_side("tears_per_s", values_of(cap, "tears_per_s"), false),
                  compare_side("warps_late / simulated seconds", one(per_second(run, "warps_late")), true),
                  Standing::converted,
                  "a runtime tears when its time warp ends after the scan has begun; latsim shows such a warp a "
                  "refresh later instead, so its late warps are counted as tears"),
      1.0, " /s");
  {
    std::vector<double> run_gpu;
    if (run.frames)
      for (const capture::PresentMonFrame& f : run.frames->frames)
        if (f.gpu_busy_ms) run_gpu.push_back(*f.gpu_busy_ms);
    add(compare_row("app_gpu", "application GPU time a frame (ms)", compare_side("app_gpu_ms", values_of(cap, "app_gpu_ms"), false),
                    compare_side("MsGPUBusy (mean)", one(run_gpu.empty() ? std::nullopt : capture::sample_stats(run_gpu).mean), true),
                    replayed("app_gpu") ? Standing::replayed : Standing::input,
                    cap.per_frame ? "" : "the capture's values are averages over a second"),
        0.5, " ms");
  }
  add(compare_row("timewarp_gpu", "time warp GPU time a frame (ms)",
                  compare_side("timewarp_gpu_ms", values_of(cap, "timewarp_gpu_ms"), false), compare_side("-", {}, true),
                  replayed("timewarp_gpu") ? Standing::replayed : Standing::no_counterpart,
                  "the run's warp cost is a scenario input, not in its files"),
      0.5, " ms");
  if (cap.find("frame_interval_ms")) {
    std::vector<double> run_interval;
    if (run.frames)
      for (const capture::PresentMonFrame& f : run.frames->frames)
        if (f.between_presents_ms) run_interval.push_back(*f.between_presents_ms);
    add(compare_row("frame_interval", "application frame interval (ms)",
                    compare_side("m_flClientFrameIntervalMs", values_of(cap, "frame_interval_ms"), false),
                    compare_side("MsBetweenPresents", run_interval, false), Standing::converted,
                    "SteamVR times the application's WaitGetPoses calls, latsim its presents: in a steady frame "
                    "loop both come once a frame"),
        0.5, " ms");
  }
}

}  // namespace latsim::sweep
