// Putting display-memory images of the priority pipelines on the display.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "latsim/arp/display_memories.hpp"
#include "latsim/pipelines/pipeline.hpp"

namespace latsim::pipelines {

/// The poses (a host sample, predicted to the photon time expected when it
/// was taken) that display-memory images may still refer to, by the tag the
/// pipeline gave the render (its tick: increasing, one pose per tick).
class SampleBook {
 public:
  void add(int64_t tag, const tracker::PosePrediction& p) { samples_.emplace(tag, p); }
  const tracker::PosePrediction& at(int64_t tag) const { return samples_.at(tag); }
  /// Drops samples older than every image the memories show: those can be
  /// neither shown nor requested again (a request is newer than its memory's shown image).
  void forget_unreachable(const arp::DisplayMemories& memories);

 private:
  std::map<int64_t, tracker::PosePrediction> samples_;
};

/// Shows a batch of images presented together: every render on the timeline
/// (unit "memory<i>"), the newest registered with the recorder as the
/// composite's image and swapped in at the next retrace.
void show_memory_images(RunContext& ctx, const std::vector<const arp::MemoryImage*>& batch, const SampleBook& samples);

}  // namespace latsim::pipelines
