// The Pixel-Planes 5 ring network as a pool of channels a transfer holds one
// of, knowing which, so every channel can be shown on a timeline.
#pragma once

#include <cstddef>
#include <vector>

#include "latsim/des/resource.hpp"

namespace latsim::pxpl5 {

/// Independent ring channels: `co_await ring.acquire()` queues first-come
/// first-served for any free channel, `claim()` then names a free one (in
/// turn, starting after the last claimed), and `release(channel)` hands it on.
class RingChannels {
 public:
  RingChannels(des::Simulator& sim, int channels);

  des::Resource::AcquireAwaiter acquire() { return pool_.acquire(); }
  /// After acquire(): marks the lowest free channel busy and returns it.
  int claim();
  void release(int channel);

  int channels() const { return static_cast<int>(busy_.size()); }
  /// Channel-seconds in use up to now, over all channels.
  des::Time unit_busy_time() const { return pool_.unit_busy_time(); }

 private:
  des::Resource pool_;
  std::vector<bool> busy_;
  std::size_t next_ = 0;  // where claim() starts looking
};

}  // namespace latsim::pxpl5
