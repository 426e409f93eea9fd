// Runs an application pacing policy inside a frame_stages pipeline: asks it
// when each frame wakes, tells it what each frame measured, falls back to
// half rate after repeated misses (and returns once the measured frame time
// fits a refresh again), and reports the pacing figures.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <vector>

#include "frame_stages/pacing.hpp"
#include "frame_stages/stage_flow.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "latsim/results/timeline.hpp"

namespace latsim::pipelines::frame_stages {

/// One paced frame as planned and as it went (kept for the first frames of a run).
struct PacedFrame {
  int64_t job = -1;
  FramePlan plan;
  FrameSample sample;
  des::Time shown;  ///< the retrace it reached: the first whose latch it made
  bool half_rate = false;
};

/// The application side of pacing for one run.
class AppPacing {
 public:
  /// `first_stages` are the application's stages, for the measured spans.
  AppPacing(const PacingSpec& spec, const std::vector<StageSpec>& stages, PacingClock clock,
            results::LatencyRecorder& recorder, results::Timeline* timeline, std::function<void(bool)> set_half_rate);

  /// When frame `rec` may wake (its first stage's start); sets its deadline to the latch.
  des::Time wake_up(JobRecord& rec, des::Time now);
  /// Frame `rec` is complete: measure it and tell the policy.
  void on_complete(const JobRecord& rec);
  /// Reports the counters.
  void finish(results::LatencyRecorder& r) const;

  /// The frames of the run so far (the first kMaxLog only).
  const std::vector<PacedFrame>& log() const { return log_; }
  bool half_rate() const { return clock_.period_multiple > 1; }

  static constexpr size_t kMaxLog = 100000;

 private:
  FrameSample measure(const JobRecord& rec, const FramePlan& plan) const;
  /// Half-rate fallback: in after `misses` of the last `window` frames
  /// missed; out after `clean_frames` in a row whose longest span fits
  /// return_threshold().
  void fall_back(const FrameSample& s);
  /// The full-rate budget (a period less the compositor's time) less the return margin.
  des::Time return_threshold() const;

  HalfRateFallbackParams fallback_;
  std::unique_ptr<AppPacer> pacer_;
  int draw_ = 0, gpu_ = 0;  ///< first stages of the draw and GPU spans
  PacingClock clock_;
  results::LatencyRecorder& recorder_;
  results::Timeline* timeline_;
  std::function<void(bool)> set_half_rate_;
  std::map<int64_t, FramePlan> plans_;  ///< frames woken, not yet complete
  std::map<int64_t, bool> planned_half_;
  std::vector<PacedFrame> log_;
  std::deque<bool> recent_misses_;
  int fitting_run_ = 0;
  int64_t misses_ = 0, half_rate_periods_ = 0, half_rate_frames_ = 0;
};

/// The first stage of the draw and of the GPU span (PacingStages, -1 resolved by runs).
PacingStages resolve_pacing_stages(const PacingStages& given, const std::vector<StageSpec>& stages);

}  // namespace latsim::pipelines::frame_stages
