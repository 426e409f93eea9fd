#include "latsim/arp/memory_render_cost.hpp"

#include <cmath>
#include <stdexcept>

namespace latsim::arp {

des::Time MemoryRenderCost::of(int64_t segments, double texels) const {
  if (segments < 0 || !(texels >= 0.0)) throw std::invalid_argument("render cost: negative segments or texels");
  const double fill_ps = std::round(per_pixel_ns * 1000.0 * texels);
  return fixed + per_segment * segments + des::Time::ps(static_cast<int64_t>(fill_ps));
}

}  // namespace latsim::arp
