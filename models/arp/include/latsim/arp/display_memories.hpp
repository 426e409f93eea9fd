// The images of a set of display memories on their way from the decision to
// redraw, through the renderers, to the screen.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "latsim/arp/memory_render_queue.hpp"
#include "latsim/arp/region_priority_model.hpp"

namespace latsim::arp {

/// One image of a display memory: what it holds and how it was drawn.
struct MemoryImage {
  int memory = 0;
  int64_t id = -1;                       ///< request id (set when requested)
  std::vector<uint32_t> contents;        ///< segments (or objects) drawn, ascending
  int64_t object_segments = 0;           ///< the same counted in object segments (the unit of the figures)
  double texels = 0.0;                   ///< cube texels covered (fill work)
  des::Time cost;                        ///< render time
  glm::dvec3 eye_m{0.0};                 ///< position it was drawn from
  int64_t sample = -1;                   ///< the caller's tag of the tracker sample that position came from
  des::Time requested;
  des::Time started;
  std::shared_ptr<const RegionView> view;  ///< region priority: what it was drawn against
};

/// Per memory, what its finished renders drew.
struct MemoryRenderCounts {
  int64_t renders = 0;
  int64_t object_segments = 0;
  int64_t drawn = 0;  ///< segments or whole objects drawn, each counting once
  double texels = 0.0;
};

/// Requests images, renders them on a MemoryRenderQueue, and keeps the image
/// each memory shows; a callback sees every batch of images presented together.
class DisplayMemories {
 public:
  using PresentFn = std::function<void(const std::vector<const MemoryImage*>& batch)>;

  DisplayMemories(des::Simulator& sim, des::KindId kind, int renderers, int memory_count);

  /// Images decided at the same instant; present_after[i] lists the memories
  /// whose newest image must be shown no later than images[i] (see MemoryRenderQueue).
  void request(std::vector<MemoryImage> images, const std::vector<std::vector<int>>& present_after);
  void on_present(PresentFn fn) { present_fn_ = std::move(fn); }

  int memory_count() const { return static_cast<int>(shown_.size()); }
  /// The image memory m shows (null before its first presentation).
  const MemoryImage* shown(int memory) const { return shown_.at(static_cast<size_t>(memory)).get(); }
  const MemoryRenderCounts& counts(int memory) const { return counts_.at(static_cast<size_t>(memory)); }
  const MemoryRenderQueue& queue() const { return queue_; }

 private:
  void presented(const std::vector<std::pair<int, int64_t>>& batch);

  des::Simulator& sim_;
  std::map<int64_t, std::shared_ptr<MemoryImage>> pending_;  // requested, not yet shown or skipped
  std::vector<std::shared_ptr<const MemoryImage>> shown_;
  std::vector<MemoryRenderCounts> counts_;
  PresentFn present_fn_;
  MemoryRenderQueue queue_;
};

}  // namespace latsim::arp
