#include "latsim/pxpl5/hardware.hpp"

#include <cmath>

namespace latsim::pxpl5 {

RegionGrid RegionGrid::for_screen(int width_px, int height_px, bool interlaced, int region_px) {
  const auto ceil_div = [](int a, int b) { return (a + b - 1) / b; };
  RegionGrid g;
  g.region_px = region_px;
  g.columns = ceil_div(width_px, region_px);
  g.rows = ceil_div(height_px, region_px);
  // A field holds every other line, so its data fill half as many region rows.
  g.field_rows = ceil_div(interlaced ? height_px / 2 : height_px, region_px);
  return g;
}

des::Time HardwareParams::transfer_time(int64_t words) const {
  return des::Time::from_us(static_cast<double>(words) / ring_mwords_per_s);
}

}  // namespace latsim::pxpl5
