// Motion-to-photon latency of the double-buffered pipeline worked out from
// the sampling phases alone, without simulating events: a self-check and an
// explanation of the simulated distribution. Its cost does not grow with the
// run: one frame (integrated phases) or one repeat cycle of frames (fixed
// ones), each a few 128-bit divisions per poll timer phase (docs/figures.md).
#pragma once

#include <optional>
#include <string>

#include "latsim/display/persistence.hpp"
#include "latsim/display/raster_timing.hpp"
#include "latsim/pipelines/run_context.hpp"
#include "latsim/tracker/tracker.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::pipelines {

/// What the analytic calculation needs to know of a run.
struct AnalyticInputs {
  display::RasterParams raster;          ///< with the nominal field period
  display::PersistenceParams persistence; ///< how each line is lit (photon time: middle of its lit interval)
  des::RationalSeconds tracker_period;   ///< nominal
  des::Time tracker_delay;               ///< internal delay
  des::Time tracker_jitter;
  const tracker::Transport* transport = nullptr;
  des::Time render_time;
  /// The phases the run used (display, tracker, poll timer).
  des::Time display_phase, tracker_phase, poll_phase;
  /// Whether the tracker's (poll timer's) phase relative to the display is
  /// integrated over: true when either clock of the pair is drawn or drifts.
  bool integrate_tracker = false;
  bool integrate_poll = false;
  /// Fields evaluated at most (the work's bound); beyond it the result is
  /// marked incomplete.
  int64_t max_fields = 4'000'000;
};

/// Motion-to-photon latency per displayed line over every phase the system
/// takes, to the middle of each line's lit interval (as the simulation measures it).
struct AnalyticLatency {
  std::string link;         ///< "direct", "serial poll" or "serial interrupt"
  std::string method;       ///< how the phases were covered
  double hyperperiod_s = 0.0;
  int64_t frames = 0;       ///< frames enumerated (per phase point when integrating)
  int64_t phase_grid = 0;   ///< points per integrated clock period (0: fixed phases)
  bool complete = true;     ///< false: the enumeration stopped at its limit of frames or fields
  double min_ms = 0.0, mean_ms = 0.0, max_ms = 0.0;
};

/// Min / mean / max motion-to-photon latency per displayed line. With fixed
/// phases: enumerated over one repeat cycle of (frame interval, tracker
/// period, poll interval), counted by field index so that the cycle holds
/// exactly its frames. With integrated phases: averaged over a grid of
/// relative phases (midpoints of equal steps of each period), each frame of
/// the steady state being alike once the phases are uniform. Returns nothing
/// when the configuration is not tractable (jitter, render-ahead, no vsync,
/// records queueing on the serial line, interrupt handler costs).
std::optional<AnalyticLatency> analytic_double_buffer(const AnalyticInputs& in);

namespace analytic {

/// The link's fixed delay after a sample is ready, and its poll timer.
struct Link {
  std::string name = "direct";
  des::Time delay;  ///< internal delay (+ transmit time on a serial line)
  std::optional<des::RationalSeconds> poll;
};

/// The link as the calculation takes it, or nothing where it needs the
/// event model (records queueing on a serial line, interrupt handler costs).
std::optional<Link> link_of(const AnalyticInputs& in);

/// Fields in one repeat cycle of the display (frames of m fields), the
/// tracker and the poll timer (each when given), or nothing when it does not
/// fit 64 bits or holds more than 64 x `max_frames` fields; `cycle_s` its length.
std::optional<int64_t> cycle_fields(des::RationalSeconds field, int64_t m, std::optional<des::RationalSeconds> tracker,
                                    std::optional<des::RationalSeconds> poll, int64_t max_frames, double& cycle_s);

}  // namespace analytic

/// A run's clocks as the analytic calculation sees them: nominal periods, the
/// phases used, which relative phases vary from run to run, and as many fields
/// as the run scans out (within bounds), for a renderer taking `render_time`.
AnalyticInputs analytic_inputs(const RunContext& ctx, des::Time render_time);

}  // namespace latsim::pipelines
