// Apparent latency: the time shift that best aligns the shown movement with
// the true one, as a camera filming the head and its image would see it.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "latsim/des/time.hpp"
#include "latsim/measurement/shown_trace.hpp"
#include "latsim/tracker/motion_phase.hpp"
#include "latsim/tracker/motion_source.hpp"

namespace latsim::measurement {

/// Settings of apparent latency (/apparent_latency).
struct ApparentLatencyParams {
  des::Time window = des::Time::ms(100);    ///< length of the sliding window of shown samples
  des::Time step = des::Time::ms(10);       ///< spacing of the window centres
  des::Time max_shift = des::Time::ms(150); ///< shifts searched: [−max_shift, max_shift]
  /// Prediction has caught up once a window's shift is at most the steady
  /// value plus this.
  double catch_up_tolerance_ms = 2.0;
  /// A movement has begun, true or shown, once it has turned this far from rest.
  double start_threshold_deg = 0.05;
};

/// The least-squares shift of one window, in milliseconds; absent when the
/// window does not determine it (the best shift lies at the edge of the
/// search, or the true movement in the window is too slow to tell shifts
/// apart).
std::optional<double> fit_shift_ms(std::span<const ShownSample> window, const tracker::MotionSource& truth,
                                   des::Time max_shift);

/// One window's result.
struct WindowShift {
  des::Time centre;
  tracker::MotionPhase phase;
  double shift_ms;
};

/// Everything apparent latency finds in a run.
struct ApparentLatencyResult {
  std::vector<WindowShift> windows;   ///< resolved windows outside rest, in time order
  int64_t unresolved = 0;             ///< windows outside rest whose shift was undetermined
  std::optional<double> steady_ms;    ///< mean shift of the steady windows
  std::vector<double> catch_up_ms;    ///< per movement start: see apparent_latency()
  int64_t never_caught_up = 0;        ///< movement starts whose shift never reached the steady value
  /// Per movement from rest: the first photon showing the head turned more
  /// than start_threshold_deg from the rest it showed, less the instant the
  /// true head first turned that far (see start_latency_ms).
  std::vector<double> start_ms;
};

/// The delay between the start of a true movement and the start of the
/// shown one: from the first instant after `start` at which the truth has
/// turned more than `threshold_deg` from its orientation at `start` (found
/// to 10 us) to the photon time of the first shown sample after `start`
/// that has turned more than that from the sample shown last before it.
/// Absent when either does not happen before `before`. No predictor can
/// shorten it below the delay of the first sample that holds the movement:
/// before then, it extrapolates a head at rest.
std::optional<double> start_latency_ms(std::span<const ShownSample> shown, const tracker::MotionSource& truth,
                                       des::Time start, des::Time before, double threshold_deg);

/// Slides a window of `params.window` over the shown samples, centred every
/// `params.step` from time zero, and fits each window's shift
/// (fit_shift_ms); a window counts in the phase of its centre, and windows
/// centred at rest are skipped. For every start of movement t0 (from
/// `phases`), the catch-up time is c − t0 for the first window centre
/// c ≥ t0, still in onset or steady motion, whose shift is at most
/// steady_ms + catch_up_tolerance_ms (none without steady windows).
ApparentLatencyResult apparent_latency(std::span<const ShownSample> shown, const tracker::MotionSource& truth,
                                       tracker::MotionPhaseClassifier& phases, const ApparentLatencyParams& params);

}  // namespace latsim::measurement
