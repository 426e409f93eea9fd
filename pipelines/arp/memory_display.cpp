#include "arp/memory_display.hpp"

#include <algorithm>
#include <string>

#include "latsim/pipelines/pipeline.hpp"
#include "latsim/results/timeline.hpp"

namespace latsim::pipelines {

void SampleBook::forget_unreachable(const arp::DisplayMemories& memories) {
  int64_t oldest = INT64_MAX;
  for (int m = 0; m < memories.memory_count(); ++m) {
    const arp::MemoryImage* img = memories.shown(m);
    if (!img) return;
    oldest = std::min(oldest, img->sample);
  }
  samples_.erase(samples_.begin(), samples_.lower_bound(oldest));
}

void show_memory_images(RunContext& ctx, const std::vector<const arp::MemoryImage*>& batch, const SampleBook& samples) {
  for (const arp::MemoryImage* img : batch) {
    const des::Time end = img->started + img->cost;
    const std::string unit = "memory" + std::to_string(img->memory);
    if (img == batch.back()) {
      ctx.present_display_memory(img->id, samples.at(img->sample), img->started, end, unit);
    } else if (ctx.timeline) {
      ctx.timeline->add("RENDER", img->id, -1, unit, img->started, end);
    }
  }
}

}  // namespace latsim::pipelines
