// How long a renderer takes to redraw a display memory.
#pragma once

#include <cstdint>

#include "latsim/des/time.hpp"

namespace latsim::arp {

/// Render time = fixed + per segment x segments drawn + per pixel x cube
/// texels the segments cover, so a small segment costs less than a whole wall.
struct MemoryRenderCost {
  des::Time fixed = des::Time::ms(1);
  des::Time per_segment = des::Time::us(20);
  double per_pixel_ns = 0.0;  ///< 0: fill is free and covered texels are not computed

  bool counts_pixels() const { return per_pixel_ns > 0.0; }
  /// Exact to the picosecond: the fill term is rounded once.
  des::Time of(int64_t segments, double texels) const;
};

}  // namespace latsim::arp
