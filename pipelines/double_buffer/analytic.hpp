// Motion-to-photon latency of the double-buffered pipeline worked out from
// the sampling phases alone, without simulating events: a self-check and an
// explanation of the simulated distribution.
#pragma once

#include <optional>

#include <nlohmann/json.hpp>

#include "latsim/display/raster_timing.hpp"
#include "latsim/tracker/tracker.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::pipelines {

/// Min / mean / max motion-to-photon latency per displayed line, enumerated
/// over one hyperperiod of (frame interval, tracker period, poll interval) —
/// the exact set of phases the system ever takes. Returns nothing when the
/// configuration is not tractable (jitter, random render time, render-ahead,
/// no vsync, records queueing on the serial line, interrupt handler costs).
std::optional<nlohmann::json> analytic_double_buffer(const display::RasterTiming& timing,
                                                     const tracker::TrackerParams& tracker,
                                                     const tracker::Transport& transport, des::Time render_time);

}  // namespace latsim::pipelines
