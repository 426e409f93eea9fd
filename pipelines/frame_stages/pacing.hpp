// Frame pacing: when the application's frame thread is let go, as today's
// runtimes decide it from what they measured of earlier frames
// (docs/pacing.md). A policy sees only measured durations and the display's
// retrace times, never the costs of frames to come.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "frame_stages/pacing_runtimes.hpp"
#include "latsim/des/time.hpp"

namespace latsim::pipelines::frame_stages {

/// Which application pacing policy runs.
enum class AppPolicy {
  fixed,         ///< the first stage's own start rule (retrace, or late): today's behaviour
  monado,        ///< Monado's u_pacing_app: IIR-smoothed CPU, draw and GPU times
  just_in_time,  ///< a percentile of the last measured frame times plus a margin (Phase Sync, Reflex)
  miss_rate,     ///< the median frame time plus a margin raised and lowered to hold a miss rate
  steamvr,       ///< SteamVR: running start, throttling (pacing_steamvr.cpp)
  oculus,        ///< Oculus PC and Quest: Phase Sync with ASW (pacing_oculus.cpp)
};

/// Monado-style application pacing (u_pacing_app). Monado's pa_create sets
/// the CPU and draw estimates to 2 ms and leaves the GPU estimate at zero.
struct MonadoAppParams {
  double iir_weight = 0.8;                     ///< new = weight * old + (1 - weight) * sample
  des::Time initial = des::Time::ms(2);        ///< the CPU and draw estimates before any frame
  des::Time initial_gpu;                       ///< the GPU estimate before any frame (Monado: zero)
  des::Time min_app_time = des::Time::ms(1);   ///< floor of their sum
  des::Time margin = des::Time::ms(2);         ///< between the predicted GPU end and the compositor's latch
};

/// Just-in-time pacing: start the frame so that it ends `margin` before the latch.
struct JustInTimeParams {
  double percentile = 99.0;                   ///< of the last `window` frame times (nearest rank)
  int window = 32;
  des::Time margin = des::Time::ms(1);
};

/// A margin controller holding missed latches per minute below a target.
struct MissRateParams {
  double target_per_min = 6.0;                   ///< missed latches per minute to stay below
  double window_s = 60.0;                        ///< misses counted over the last this long
  int median_window = 32;                        ///< frame times the median is taken over
  des::Time initial_margin = des::Time::ms(2);
  des::Time raise = des::Time::us(500);          ///< added to the margin at each miss
  des::Time lower = des::Time::us(2);            ///< taken off per clean frame while one more miss keeps the target
};

/// Falls back to half rate (the compositor synthesising every other refresh)
/// after repeated misses, and returns only once the measured frame time fits
/// the full-rate budget with a margin to spare (hysteresis: the time that
/// forced the fallback does not end it).
struct HalfRateFallbackParams {
  bool enabled = false;
  int misses = 3;         ///< misses among the last `window` frames that force half rate
  int window = 10;
  int clean_frames = 45;  ///< consecutive frames whose measured time fits that return to full rate
  double return_margin_percent = 10.0;  ///< of the refresh period: the full-rate budget less this must hold the time
};

/// Monado-style compositor pacing (u_pacing_compositor with display timing):
/// its comp_time is the budget here, its margin_ns the target margin.
struct CompositorPacingParams {
  bool enabled = false;             ///< false: the warp's own late rule
  double initial_percent = 10.0;    ///< of the refresh period: the first budget
  double max_percent = 30.0;        ///< the ceiling a miss's step is held to
  double miss_step_percent = 4.0;   ///< added after a miss
  double step_percent = 2.0;        ///< step towards the target margin; also the band's half width
  des::Time target_margin = des::Time::ms(1);  ///< wanted between the warp's end and its deadline
  des::Time late_slop = des::Time::us(500);    ///< shown this much or more after its deadline: a miss
};

/// Where the application's measured spans begin (stage indices); -1: by runs
/// (the GPU span from the last run's first stage, the draw span from the run
/// before it).
struct PacingStages {
  int draw = -1;
  int gpu = -1;
};

/// The pacing of a frame_stages pipeline, as the scenario selects it.
struct PacingSpec {
  AppPolicy app = AppPolicy::fixed;
  MonadoAppParams monado;
  JustInTimeParams just_in_time;
  MissRateParams miss_rate;
  HalfRateFallbackParams half_rate;
  CompositorPacingParams compositor;
  PacingStages stages;
  SteamVrParams steamvr;
  OculusParams oculus;
};

/// What the runtime measured of one application frame.
struct FrameSample {
  des::Time woke;      ///< the thread was let go
  des::Time cpu;       ///< woke to the draw span's start
  des::Time draw;      ///< the draw (submission) span
  des::Time gpu;       ///< the submission's end to the GPU's end
  des::Time gpu_done;
  des::Time latch;     ///< when the compositor (or the retrace) took frames
  bool missed = false; ///< done after its latch
  /// The longest of the cpu, draw and gpu spans: with each on its own thread
  /// or GPU and frames overlapping, the span that bounds the frame rate.
  des::Time longest_span() const;
};

/// The display as a policy sees it, and what it plans around.
struct PacingClock {
  des::Time period;                              ///< refresh period
  std::function<des::Time(des::Time)> next_display;  ///< first retrace at or after t
  std::function<des::Time()> compositor_time;    ///< how long before a retrace the compositor latches
  int period_multiple = 1;                       ///< 2 at half rate: frames at least two refreshes apart
  /// Stages that start with the next frame (next_frame): each puts the
  /// frame's display one more refresh after its wake-up.
  int handovers = 0;
  /// Tells the compositor how many refreshes each new frame is planned to be
  /// shown in (the extra ones synthesised, not missed); absent without one.
  std::function<void(int)> set_planned_showings;
};

/// One frame's plan: when it wakes, when it should be done, where it is shown.
struct FramePlan {
  des::Time wake_up;
  des::Time predicted_done;  ///< wake_up plus the predicted application time
  des::Time latch;           ///< display minus the compositor's time
  des::Time display;         ///< the retrace it is meant for
  int frame_periods = 1;     ///< refreshes the policy spaces frames by
  /// The frame is shown from `display` and not before, even when done
  /// earlier, and is predicted for it (SteamVR: "a frame will never be
  /// displayed before the vsync interval it was predicted to").
  bool hold = false;
};

/// A pacing policy: plans each frame, learns from each measured one.
class AppPacer {
 public:
  virtual ~AppPacer() = default;
  /// The plan for the next frame, asked at `now` when its thread is ready.
  virtual FramePlan plan(des::Time now, const PacingClock& clock) = 0;
  virtual void measured(const FrameSample& sample) = 0;
  /// Counters the policy reports at the end of the run (name, value).
  virtual std::vector<std::pair<std::string, int64_t>> counters() const { return {}; }
};

/// The plan for a frame that needs `lead` before its latch and a frame period
/// of `frame_periods` refreshes: the first retrace at least that long after
/// `last_display` whose wake-up is not before `now`.
FramePlan plan_for(des::Time now, des::Time app_time, des::Time margin, int frame_periods, des::Time last_display,
                   const PacingClock& clock);

/// The pacer of a policy (fixed: none).
std::unique_ptr<AppPacer> make_app_pacer(const PacingSpec& spec);

}  // namespace latsim::pipelines::frame_stages
