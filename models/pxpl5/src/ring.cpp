#include "latsim/pxpl5/ring.hpp"

#include <stdexcept>

namespace latsim::pxpl5 {

RingChannels::RingChannels(des::Simulator& sim, int channels)
    : pool_(sim, channels, "pxpl5.ring"), busy_(static_cast<std::size_t>(channels), false) {}

int RingChannels::claim() {
  // The pool hands out as many units as there are channels, so a holder of a
  // unit always finds a channel free. Channels are taken in turn from the one
  // after the last claimed, so the traffic (and the timeline) spreads over
  // every channel rather than piling on the first.
  const std::size_t n = busy_.size();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t c = (next_ + k) % n;
    if (!busy_[c]) {
      busy_[c] = true;
      next_ = (c + 1) % n;
      return static_cast<int>(c);
    }
  }
  throw std::logic_error("RingChannels::claim() without a channel acquired");
}

void RingChannels::release(int channel) {
  if (channel < 0 || channel >= channels() || !busy_[static_cast<std::size_t>(channel)])
    throw std::logic_error("RingChannels::release() of a channel not in use");
  busy_[static_cast<std::size_t>(channel)] = false;
  pool_.release();
}

}  // namespace latsim::pxpl5
