// Monado-style compositor pacing (u_pacing_compositor with display-timing
// feedback): the compositor's own time budget before each deadline, adjusted
// from how early or late each warp was done (docs/pacing.md).
#pragma once

#include <cstdint>

#include "frame_stages/pacing.hpp"
#include "frame_stages/stage_flow.hpp"
#include "frame_stages/warp_clock.hpp"
#include "latsim/results/figure_writer.hpp"

namespace latsim::pipelines::frame_stages {

/// The warp starts `budget` before its deadline. The budget starts at
/// initial_percent of the period (its floor), rises by miss_step_percent
/// after a warp shown more than late_slop after its deadline, and otherwise
/// steps by step_percent towards a margin (deadline minus the warp's end) of
/// target_margin, leaving it alone within step_percent of it; never above max_percent.
class CompositorPacer {
 public:
  CompositorPacer(const CompositorPacingParams& p, des::Time period, const WarpClock& clock);

  des::Time budget() const { return budget_; }
  /// When warp `rec` may start; sets its deadline (one not aimed for before).
  des::Time wake_up(JobRecord& rec, des::Time now);
  /// Warp `rec` has ended: adjust the budget.
  void on_complete(const JobRecord& rec, results::FigureWriter& figures);
  void finish(results::FigureWriter& r) const;

 private:
  des::Time percent_of_period(double percent) const;

  CompositorPacingParams p_;
  des::Time period_;
  const WarpClock& clock_;
  des::Time budget_, min_, max_, miss_step_, step_;
  des::Time last_deadline_ = des::Time::ps(-1);
  int64_t misses_ = 0;
};

}  // namespace latsim::pipelines::frame_stages
