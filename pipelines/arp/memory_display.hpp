// Putting display-memory images of the priority pipelines on the display.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "latsim/arp/display_memories.hpp"
#include "latsim/pipelines/pipeline.hpp"

namespace latsim::pipelines {

/// The tracker samples that display-memory images may still refer to, by index.
class SampleBook {
 public:
  void add(const tracker::TrackerSample& s) { samples_.emplace(s.index, s); }
  const tracker::TrackerSample& at(int64_t index) const { return samples_.at(index); }
  /// Drops samples older than every image the memories show: those can be
  /// neither shown nor requested again (a request is newer than its memory's shown image).
  void forget_unreachable(const arp::DisplayMemories& memories);

 private:
  std::map<int64_t, tracker::TrackerSample> samples_;
};

/// Shows a batch of images presented together: every render on the timeline
/// (unit "memory<i>"), the newest registered with the recorder as the
/// composite's image and swapped in at the next retrace.
void show_memory_images(RunContext& ctx, const std::vector<const arp::MemoryImage*>& batch, const SampleBook& samples);

}  // namespace latsim::pipelines
