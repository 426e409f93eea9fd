#include "latsim/arp/display_memories.hpp"

#include <stdexcept>

namespace latsim::arp {

DisplayMemories::DisplayMemories(des::Simulator& sim, des::KindId kind, int renderers, int memory_count)
    : sim_(sim),
      shown_(static_cast<size_t>(std::max(memory_count, 1))),
      counts_(static_cast<size_t>(std::max(memory_count, 1))),
      queue_(sim, kind, renderers, memory_count,
             MemoryRenderQueue::Listener{
                 .started = [this](int, int64_t id) { pending_.at(id)->started = sim_.now(); },
                 .finished =
                     [this](int memory, int64_t id) {
                       const MemoryImage& img = *pending_.at(id);
                       MemoryRenderCounts& c = counts_[static_cast<size_t>(memory)];
                       ++c.renders;
                       c.object_segments += img.object_segments;
                       c.drawn += static_cast<int64_t>(img.contents.size());
                       c.texels += img.texels;
                     },
                 .presented = [this](const std::vector<std::pair<int, int64_t>>& batch) { presented(batch); },
                 .skipped = [this](int, int64_t id) { pending_.erase(id); }}) {}

void DisplayMemories::request(std::vector<MemoryImage> images, const std::vector<std::vector<int>>& present_after) {
  if (present_after.size() != images.size())
    throw std::invalid_argument("display memories: one present_after list per image");
  std::vector<MemoryRenderQueue::Update> updates;
  for (size_t i = 0; i < images.size(); ++i) updates.push_back({images[i].memory, images[i].cost, present_after[i]});
  // Ids are known only after the request; the queue starts renders within it,
  // so the images are filed first under the ids it will give them.
  const int64_t first = queue_.next_id();
  for (size_t i = 0; i < images.size(); ++i) {
    auto img = std::make_shared<MemoryImage>(std::move(images[i]));
    img->id = first + static_cast<int64_t>(i);
    pending_.emplace(img->id, std::move(img));
  }
  queue_.request(updates);
}

void DisplayMemories::presented(const std::vector<std::pair<int, int64_t>>& batch) {
  // A batch may hold several images of one memory: all stay alive until the
  // callback has seen them, though only the newest stays shown.
  std::vector<std::shared_ptr<const MemoryImage>> keep;
  std::vector<const MemoryImage*> images;
  for (const auto& [memory, id] : batch) {
    auto it = pending_.find(id);
    keep.push_back(it->second);
    shown_[static_cast<size_t>(memory)] = it->second;
    images.push_back(it->second.get());
    pending_.erase(it);
  }
  if (present_fn_) present_fn_(images);
}

}  // namespace latsim::arp
