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

HardwareParams HardwareParams::read(const scenario::ConfigNode& p) {
  HardwareParams h;
  h.ring_channels = static_cast<int>(p.integer("ring_channels", h.ring_channels, 1, 64));
  h.ring_mwords_per_s = p.positive("ring_mwords_per_s", h.ring_mwords_per_s);
  h.renderers = static_cast<int>(p.integer("renderers", h.renderers, 1, 256));
  h.frame_buffers = static_cast<int>(p.integer("frame_buffers", h.frame_buffers, 1, 2));
  h.words_per_command = static_cast<int>(p.integer("words_per_command", h.words_per_command, 1, 4096));
  h.max_message_words = static_cast<int>(p.integer("max_message_words", h.max_message_words, 1, 1 << 20));
  if (h.max_message_words < h.words_per_command)
    p.fail("max_message_words", "must hold at least one command (words_per_command)");
  h.copy_time_per_region = des::Time::from_us(p.positive("copy_us_per_region", 780.0));
  h.render_time_per_command = des::Time::from_us(p.non_negative("render_us_per_command", 6.0));
  return h;
}

}  // namespace latsim::pxpl5
