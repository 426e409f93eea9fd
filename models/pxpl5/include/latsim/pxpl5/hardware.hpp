// The Pixel-Planes 5 machine as a set of timing parameters (SPEC.md section 3).
#pragma once

#include <cstdint>

#include "latsim/des/time.hpp"

namespace latsim::pxpl5 {

/// Screen tiling into renderer regions: whole-frame regions and, for
/// interlaced display, the half-height field regions each field needs.
struct RegionGrid {
  int region_px = 128;
  int columns = 5;              ///< ceil(width / region_px)
  int rows = 4;                 ///< ceil(height / region_px), full frame
  int field_rows = 2;           ///< ceil(lines per field / region_px)

  int regions() const { return columns * rows; }
  int field_regions() const { return columns * field_rows; }
  /// 640 x 480 gives 5 x 4 = 20 regions and, interlaced, 5 x 2 = 10 per field.
  static RegionGrid for_screen(int width_px, int height_px, bool interlaced, int region_px);
};

/// Ring network, renderer and frame-buffer figures shared by both pipelines.
struct HardwareParams {
  int ring_channels = 8;                ///< independent channels of the ring
  double ring_mwords_per_s = 20.0;      ///< per channel (8 x 20 = 160 Mwords/s in all)
  int renderers = 5;
  int frame_buffers = 2;                ///< one per eye in stereo
  int words_per_command = 24;           ///< one Gouraud triangle for one eye: edge, z and colour planes
  int max_message_words = 1024;         ///< largest ring message
  des::Time copy_time_per_region = des::Time::us(780);  ///< renderer -> frame buffer, one region
  des::Time render_time_per_command = des::Time::from_us(4.6); ///< one triangle command into one region

  /// Time for `words` to cross one ring channel.
  des::Time transfer_time(int64_t words) const;
};

}  // namespace latsim::pxpl5
