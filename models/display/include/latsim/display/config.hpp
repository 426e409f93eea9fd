// Reading a display description from a scenario's /display object.
#pragma once

#include "latsim/display/display.hpp"
#include "latsim/display/raster_timing.hpp"
#include "latsim/scenario/config.hpp"

namespace latsim::display {

/// Everything /display describes.
struct DisplayConfig {
  RasterParams raster;
  double hfov_deg = 90.0;
  ScanoutFidelity fidelity = ScanoutFidelity::Field;
  int pixel_stride = 1;
};

/// Parses {"refresh_hz": 60 | "60000/1001", "interlaced", "width_px", "height_px",
/// "vblank_lines", "hblank_px", "hfov_deg", "scanout": "field"|"line"|"pixel",
/// "pixel_stride"}. For interlaced displays refresh_hz is the field rate.
DisplayConfig parse_display(const scenario::ConfigNode& node);

}  // namespace latsim::display
