// Monado-style compositor pacing (u_pacing_compositor with display-timing
// feedback): the compositor's own time budget before each deadline, adjusted
// from how early or late each warp was done (docs/pacing.md quotes the rules).
#pragma once

#include <cstdint>

#include "frame_stages/pacing.hpp"
#include "frame_stages/stage_flow.hpp"
#include "frame_stages/warp_clock.hpp"
#include "latsim/results/latency_recorder.hpp"

namespace latsim::pipelines::frame_stages {

/// Wakes the warp `budget + target_margin` before its deadline (Monado's
/// wake_up_time = desired_present_time - (comp_time + margin)). The budget
/// starts at initial_percent of the period; after a warp shown late_slop or
/// more after its deadline it rises by miss_step_percent, held to at most
/// max_percent (the only place Monado bounds it); otherwise it steps by
/// step_percent towards a margin (deadline minus the warp's end) of
/// target_margin, left alone within step_percent of it, without bounds.
class CompositorPacer {
 public:
  CompositorPacer(const CompositorPacingParams& p, des::Time period, const WarpClock& clock);

  /// Monado's comp_time: the compositor's estimate of its own work.
  des::Time budget() const { return budget_; }
  /// How long before a deadline the compositor wakes: the budget and the margin.
  des::Time lead() const { return budget_ + p_.target_margin; }
  /// When warp `rec` may start; sets its deadline (the first one strictly
  /// after now + lead() not aimed for before).
  des::Time wake_up(JobRecord& rec, des::Time now);
  /// Warp `rec` has ended: adjust the budget.
  void on_complete(const JobRecord& rec, results::LatencyRecorder& recorder);
  void finish(results::LatencyRecorder& r) const;

 private:
  des::Time percent_of_period(double percent) const;

  CompositorPacingParams p_;
  des::Time period_;
  const WarpClock& clock_;
  des::Time budget_, max_, miss_step_, step_;
  des::Time last_deadline_ = des::Time::ps(-1);
  int64_t misses_ = 0;
};

}  // namespace latsim::pipelines::frame_stages
