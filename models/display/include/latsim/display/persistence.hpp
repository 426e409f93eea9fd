// Display persistence: from when, and for how long, a written pixel emits
// light; the photon time of latency figures is the middle of that interval.
#pragma once

#include <cstdint>

#include "latsim/stats/tick_run.hpp"
#include "latsim/des/time.hpp"
#include "latsim/display/raster_timing.hpp"

namespace latsim::display {

/// How a panel lights a pixel once scanout has written it.
struct PersistenceParams {
  enum class Mode {
    impulse,  ///< no persistence configured: photons at the scanout instant (as a CRT)
    full,     ///< sample and hold: lit until the row is written again
    rolling,  ///< each row flashes for `lit` once it has settled
    global,   ///< the whole panel flashes for `lit` once every row has been written and settled
  };
  Mode mode = Mode::impulse;
  des::Time lit;       ///< rolling / global: flash length (0 < lit <= frame period)
  des::Time response;  ///< pixel response: the whole transition from the old value to the new one
  /// The shape of that transition as a camera filming the panel sees it
  /// (the lit intervals, and so every latency figure, do not depend on it):
  /// step: the new value whenever the pixel is lit; linear: over `response`
  /// (OLED); exponential: 10 % to 90 % in `response` (an LCD's grey to grey).
  enum class Rise { step, linear, exponential };
  Rise rise = Rise::step;
};

/// When one written pixel is lit.
struct LitInterval {
  des::Time on;        ///< light starts (for full persistence: the new value crosses 50 %)
  des::Time duration;  ///< 0 for an impulse
  des::Time middle() const { return on + des::Time::ps(duration.ticks() / 2); }
};

/// Lit intervals of pixels, from the raster timing and the panel's persistence.
///
/// With written time w, response time r and frame period T (the time until
/// the same row is written again):
///   impulse: [w, w];   full: [w + r/2, w + r/2 + T] (a linear transition of
///   length r crosses 50 % halfway, the next write's crossing ends the value);
///   rolling: [w + r, w + r + lit] (the flash waits until the row has settled);
///   global:  [e + r, e + r + lit], e = end of the field's active scanout, the
///   same for every pixel of the field.
class Persistence {
 public:
  Persistence() = default;
  /// Throws std::invalid_argument when lit is not in (0, frame period] for
  /// rolling and global, or the response time is negative.
  Persistence(PersistenceParams params, const RasterTiming& timing);

  const PersistenceParams& params() const { return params_; }
  /// False for the impulse model, which costs nothing per pixel.
  bool configured() const { return params_.mode != PersistenceParams::Mode::impulse; }
  /// The lit interval of a pixel of `field` written at `written`.
  LitInterval lit(int64_t field, des::Time written) const;
  /// The middles of the lit intervals of pixels of `field` written at the
  /// instants of `written`: those instants moved by one constant of the
  /// field, or, for a global flash, one instant for all.
  stats::TickRun photons(int64_t field, const stats::TickRun& written) const;

 private:
  PersistenceParams params_;
  RasterTiming timing_;
};

}  // namespace latsim::display
