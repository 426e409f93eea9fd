// When a compositor's work is due: at each retrace, or, warping strip by
// strip, when the first line of each strip is lit.
#pragma once

#include <cstdint>

#include "latsim/des/time.hpp"
#include "latsim/display/raster_timing.hpp"

namespace latsim::pipelines::frame_stages {

/// Deadlines of a compositor that warps whole fields (one strip: due at the
/// retrace, where the swap happens) or strips written into the front buffer
/// (due when the strip's first line is lit).
class WarpClock {
 public:
  /// Which strip of which field a deadline belongs to.
  struct Slot {
    int64_t field = 0;
    int strip = 0;
  };

  WarpClock(const display::RasterTiming& timing, int strips);

  int strips() const { return strips_; }
  /// First line of strip s (strips split the field's lines as evenly as integers allow).
  int first_line(int strip) const;
  des::Time deadline(Slot slot) const;
  /// The first deadline at or after t.
  des::Time next_deadline(des::Time t) const;
  /// The slot whose deadline is d (d must be a deadline).
  Slot slot_of(des::Time d) const;
  /// The middle line of strip s (its photon time, through the display's
  /// persistence, is what a warp of the strip predicts for).
  int middle_line(int strip) const;

 private:
  display::RasterTiming timing_;
  int strips_;
};

}  // namespace latsim::pipelines::frame_stages
