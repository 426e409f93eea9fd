#include "latsim/display/config.hpp"

namespace latsim::display {

DisplayConfig parse_display(const scenario::ConfigNode& node) {
  DisplayConfig c;
  c.raster.field_period = node.rate_as_period("refresh_hz", "60");
  c.raster.interlaced = node.boolean("interlaced", false);
  c.raster.width_px = static_cast<int>(node.integer("width_px", 640, 1, 16384));
  c.raster.height_px = static_cast<int>(node.integer("height_px", 480, 2, 16384));
  if (c.raster.interlaced && c.raster.height_px % 2 != 0)
    node.fail("height_px", "an interlaced display needs an even number of lines");
  c.raster.vblank_lines = static_cast<int>(node.integer("vblank_lines", 22, 0, 100000));
  c.raster.hblank_px = static_cast<int>(node.integer("hblank_px", 160, 0, 100000));
  c.raster.first_field_parity = static_cast<int>(node.integer("first_field_parity", 0, 0, 1));
  c.hfov_deg = node.number_in("hfov_deg", 90.0, 1.0, 179.0);
  const std::string s = node.choice("scanout", "field", {"field", "line", "pixel"});
  c.fidelity = s == "field" ? ScanoutFidelity::Field : s == "line" ? ScanoutFidelity::Line : ScanoutFidelity::Pixel;
  c.pixel_stride = static_cast<int>(node.integer("pixel_stride", 1, 1, 16384));
  return c;
}

}  // namespace latsim::display
