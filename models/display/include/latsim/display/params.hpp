// Everything the scenario's "display" object describes, as a plain struct.
#pragma once

#include <optional>

#include "latsim/des/clock.hpp"
#include "latsim/display/clock_noise.hpp"
#include "latsim/display/display.hpp"
#include "latsim/display/persistence.hpp"
#include "latsim/display/raster_timing.hpp"

namespace latsim::display {

/// One display: its raster, field of view, how finely scanout is simulated
/// and how long its pixels stay lit.
struct DisplayParams {
  RasterParams raster;
  double hfov_deg = 90.0;
  ScanoutFidelity fidelity = ScanoutFidelity::Field;
  int pixel_stride = 1;
  bool pixel_events = false;  ///< pixel fidelity: one event per pixel (the reference) instead of per line
  /// How long a written pixel is lit; none: at its scanout instant only.
  std::optional<PersistenceParams> persistence;
  /// The display's oscillator: retrace phase and refresh rate error.
  des::ClockSettings clock;
  /// The oscillator's jitter and wander (none: a steady clock).
  std::optional<ClockNoiseParams> clock_noise;
};

}  // namespace latsim::display
