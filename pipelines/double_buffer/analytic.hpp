// Motion-to-photon latency of the double-buffered pipeline worked out from
// the sampling phases alone, without simulating events: a self-check and an
// explanation of the simulated distribution.
#pragma once

#include <optional>
#include <string>

#include "latsim/display/raster_timing.hpp"
#include "latsim/tracker/tracker.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::pipelines {

/// Motion-to-photon latency over every phase the system takes.
struct AnalyticLatency {
  std::string link;        ///< "direct", "serial poll" or "serial interrupt"
  double hyperperiod_s = 0.0;
  int64_t frames = 0;
  bool complete = true;    ///< false: the enumeration stopped at its frame limit
  double min_ms = 0.0, mean_ms = 0.0, max_ms = 0.0;
};

/// Min / mean / max motion-to-photon latency per displayed line, enumerated
/// over one hyperperiod of (frame interval, tracker period, poll interval) —
/// the exact set of phases the system ever takes. Returns nothing when the
/// configuration is not tractable (jitter, random render time, render-ahead,
/// no vsync, records queueing on the serial line, interrupt handler costs).
std::optional<AnalyticLatency> analytic_double_buffer(const display::RasterTiming& timing,
                                                     const tracker::TrackerParams& tracker,
                                                     const tracker::Transport& transport, des::Time render_time);

}  // namespace latsim::pipelines
