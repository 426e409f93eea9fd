// SteamVR's and the Oculus runtimes' application pacing (docs/pacing.md),
// as their documentation and Valve's throttling patent describe them; no
// code of either runtime.
#include "frame_stages/pacing_runtime_pacers.hpp"

#include <algorithm>
#include <optional>

#include "frame_stages/pacing_jit.hpp"

namespace latsim::pipelines::frame_stages {

namespace {

des::Time half_of(des::Time t) { return des::Time::ps(t.ticks() / 2); }

/// Keeps the compositor told how many refreshes each frame is shown in.
class Showings {
 public:
  void tell(int n, const PacingClock& clock) {
    if (n == told_ || !clock.set_planned_showings) return;
    clock.set_planned_showings(n);
    told_ = n;
  }

 private:
  int told_ = 1;
};

/// SteamVR: WaitGetPoses returns `running_start` before a retrace V, at the
/// first such point the application can still make (its thread is ready by
/// then), for a frame shown from V + (1 + handovers + level) refreshes:
/// one refresh to render, one more per render thread behind the game thread,
/// one more per throttle level (the prediction level rises with it). At
/// throttle level L frames are L + 1 refreshes apart and the compositor
/// re-projects (or synthesises) the others. A frame is late when its thread
/// was not ready for the running start its rate needs, or it missed its
/// latch; early, at a level above 0, when it would have made the level below.
class SteamVrPacer final : public AppPacer {
 public:
  explicit SteamVrPacer(const SteamVrParams& p) : p_(p), throttle_(limits(p)) {}

  FramePlan plan(des::Time now, const PacingClock& clock) override {
    period_ = clock.period;
    handovers_ = clock.handovers;
    const des::Time half = half_of(clock.period);
    if (last_wake_) judge(now, clock);
    const int level = throttle_.level();
    const int n = level + 1;
    showings_.tell(n, clock);
    // The first running start the thread can make, n refreshes after the last display's.
    des::Time v = clock.next_display(now + p_.running_start);
    const int ahead = 1 + clock.handovers + level;
    while (last_display_ && v + clock.period * ahead < *last_display_ + clock.period * n - half)
      v = clock.next_display(v + half);
    FramePlan plan;
    plan.wake_up = v - p_.running_start;
    plan.display = clock.next_display(v + clock.period * ahead - half);
    plan.latch = plan.display - clock.compositor_time();
    plan.predicted_done = plan.wake_up + (frame_time_ > des::Time::zero() ? frame_time_ : clock.period);
    plan.frame_periods = n;
    plan.hold = true;
    if (level > 0) ++throttled_frames_;
    last_display_ = plan.display;
    last_wake_ = plan.wake_up;
    return plan;
  }

  void measured(const FrameSample& s) override {
    frame_time_ = s.gpu_done - s.woke;
    // A frame that slipped hands its render thread's work over late too, so it
    // misses its latch as well: one late frame, counted once.
    latch_missed_ = latch_missed_ || (s.missed && s.woke != slipped_wake_);
    // At the level below, frames start a refresh sooner, so each hand-over to
    // the next frame's start (a render thread a frame behind) comes a refresh
    // sooner, and so does the latch: judged at this level alone, a pipelined
    // engine's GPU would never look early and the level would never fall.
    gpu_early_ = gpu_early_ && s.gpu_done - period_ * handovers_ <= s.latch - period_;
  }

  std::vector<std::pair<std::string, int64_t>> counters() const override {
    return {{"throttle_raised", throttle_.raised()}, {"throttled_frames", throttled_frames_}};
  }

 private:
  static ThrottleParams limits(const SteamVrParams& p) {
    ThrottleParams t = p.throttle;
    switch (p.reprojection) {
      case SteamVrParams::Reprojection::off: t.max_level = 0; break;
      case SteamVrParams::Reprojection::interleaved: t.max_level = 1; break;
      case SteamVrParams::Reprojection::motion_smoothing: t.max_level = 3; break;
    }
    return t;
  }

  /// The previous frame, now that its thread is ready for the next one.
  void judge(des::Time now, const PacingClock& clock) {
    const des::Time half = half_of(clock.period);
    const int n = throttle_.level() + 1;
    const des::Time first_possible = clock.next_display(now + p_.running_start) - p_.running_start;
    const bool slipped = first_possible > *last_wake_ + clock.period * n + half;
    const bool ready_early = n > 1 && first_possible <= *last_wake_ + clock.period * (n - 1) + half;
    if (slipped) slipped_wake_ = *last_wake_;
    throttle_.frame(slipped || latch_missed_, ready_early && gpu_early_);
    latch_missed_ = false;
    gpu_early_ = true;
  }

  SteamVrParams p_;
  RuntimeThrottle throttle_;
  Showings showings_;
  des::Time period_ = des::Time::max();
  int handovers_ = 0;
  des::Time frame_time_;
  std::optional<des::Time> last_display_, last_wake_;
  des::Time slipped_wake_ = des::Time::max();  // the last frame judged late for slipping, by its wake-up
  bool latch_missed_ = false;
  bool gpu_early_ = true;
  int64_t throttled_frames_ = 0;
};

/// Oculus: Phase Sync wakes the frame its `percentile` of recent frame
/// times plus `margin` before the compositor's latch (as just_in_time);
/// with ASW, a frame whose display slipped past the rate it was planned
/// for, or that missed its latch, counts as late, and after enough of them
/// the application is held to half rate while the compositor synthesises
/// every other refresh, until frames fit a full-rate refresh again.
class OculusPacer final : public AppPacer {
 public:
  explicit OculusPacer(const OculusParams& p) : p_(p), spans_(p.window), throttle_(limits(p)) {}

  FramePlan plan(des::Time now, const PacingClock& clock) override {
    period_ = clock.period;
    handovers_ = clock.handovers;
    comp_ = clock.compositor_time();
    const int n = throttle_.level() + 1;
    showings_.tell(n, clock);
    const des::Time app = spans_.empty() ? clock.period * (1 + clock.handovers) : spans_.percentile(p_.percentile);
    const FramePlan plan = plan_for(now, app, p_.margin, std::max(n, clock.period_multiple),
                                    last_display_ ? *last_display_ : des::Time::ps(-1), clock);
    if (last_display_) {
      const bool slipped = plan.display > *last_display_ + clock.period * n + half_of(clock.period);
      pending_late_ = pending_late_ || slipped;
    }
    if (n > 1) ++throttled_frames_;
    last_display_ = plan.display;
    return plan;
  }

  void measured(const FrameSample& s) override {
    const des::Time frame_time = s.gpu_done - s.woke;
    spans_.add(frame_time);
    const bool late = pending_late_ || s.missed;
    pending_late_ = false;
    // Would fit a full-rate refresh, margin and compositor included.
    const bool early = frame_time + p_.margin + comp_ <= period_ * (1 + handovers_);
    throttle_.frame(late, early);
  }

  std::vector<std::pair<std::string, int64_t>> counters() const override {
    return {{"throttle_raised", throttle_.raised()}, {"throttled_frames", throttled_frames_}};
  }

 private:
  static ThrottleParams limits(const OculusParams& p) {
    ThrottleParams t = p.throttle;
    t.max_level = p.asw ? std::min(t.max_level, 1) : 0;
    return t;
  }

  OculusParams p_;
  RecentSpans spans_;
  RuntimeThrottle throttle_;
  Showings showings_;
  des::Time period_ = des::Time::max();
  des::Time comp_;
  int handovers_ = 0;
  std::optional<des::Time> last_display_;
  bool pending_late_ = false;
  int64_t throttled_frames_ = 0;
};

}  // namespace

std::unique_ptr<AppPacer> make_steamvr_pacer(const SteamVrParams& p) { return std::make_unique<SteamVrPacer>(p); }
std::unique_ptr<AppPacer> make_oculus_pacer(const OculusParams& p) { return std::make_unique<OculusPacer>(p); }

}  // namespace latsim::pipelines::frame_stages
