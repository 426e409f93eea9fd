// How busy a run will be, declared before it starts: every model and pipeline
// names the scenario key that drives each of its event sources and how many
// events per simulated second that source makes. A run sums rate × duration
// to refuse, with that key, a scenario whose run could never finish (a 1 ps
// render time); see docs/event-budget.md.
#pragma once

#include <string>
#include <vector>

#include "latsim/des/time.hpp"
#include "latsim/sections/shared.hpp"

namespace latsim::pipelines {

/// One source of events (or of steps of work done without events) and the key that drives it.
struct EventRate {
  std::string pointer;  ///< the key, or the object of several keys, whose value sets the rate
  std::string model;    ///< whose events: the prefix summary.json's events_per_model uses
  double per_s = 0.0;   ///< events (or steps) per simulated second
  /// Steps of work that are not events (pixels computed, motion-phase grid
  /// steps): they count against the budget, not in summary.json's events.
  bool steps = false;
};

/// Per second, one per `period`: 1 / period, or `cap_hz` when that is lower
/// or the period is zero (work paced by something else, such as retraces).
double paced_per_s(des::Time period, double cap_hz);
/// The same for a period in seconds (a sum of times that need not fit des::Time).
double paced_per_s(double period_s, double cap_hz);

/// The rates of the shared models: the tracker's samples (/tracker/rate_hz),
/// a serial link's line events, the display's retraces and scanout events
/// (/display/refresh_hz, /display/scanout, /display/pixel_stride) and the
/// motion-phase grid (/motion_phases/step_ms).
std::vector<EventRate> shared_event_rates(const sections::SharedParams& p);

}  // namespace latsim::pipelines
