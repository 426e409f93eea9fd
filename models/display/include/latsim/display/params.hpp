// Everything the scenario's "display" object describes, as a plain struct.
#pragma once

#include "latsim/display/display.hpp"
#include "latsim/display/raster_timing.hpp"

namespace latsim::display {

/// One display: its raster, field of view and how finely scanout is simulated.
struct DisplayParams {
  RasterParams raster;
  double hfov_deg = 90.0;
  ScanoutFidelity fidelity = ScanoutFidelity::Field;
  int pixel_stride = 1;
};

}  // namespace latsim::display
