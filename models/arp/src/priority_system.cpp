#include "latsim/arp/priority_system.hpp"

#include <algorithm>
#include <stdexcept>

#include "latsim/arp/covered_texels.hpp"

namespace latsim::arp {

PrioritySystem::PrioritySystem(des::Simulator& sim, des::KindId render_kind, const renderer::Scene& scene,
                               std::vector<PriorityObject> objects, PrioritySystemParams params)
    : scene_(scene),
      params_(params),
      model_(std::move(objects), params.model),
      memories_(sim, render_kind, params.renderers, params.model.memory_count) {
  if (model_.assignment().size() != scene.object_count())
    throw std::invalid_argument("priority system: one priority object per scene object");
}

const PriorityTick& PrioritySystem::tick(int64_t k, des::Time now, const glm::dvec3& eye_m,
                                         const glm::dvec3& velocity_m_s, int64_t sample) {
  last_tick_ = model_.tick(k, now, eye_m, velocity_m_s);
  if (last_tick_.updated_memories.empty()) return last_tick_;
  const auto lists = model_.objects_per_memory();
  std::vector<MemoryImage> images;
  std::vector<std::vector<int>> after;
  for (int m : last_tick_.updated_memories) {
    MemoryImage img;
    img.memory = m;
    img.contents = lists[static_cast<size_t>(m)];
    img.object_segments = static_cast<int64_t>(img.contents.size());
    img.eye_m = eye_m;
    img.sample = sample;
    if (params_.cost.counts_pixels()) {
      for (uint32_t o : img.contents) img.texels += object_texels(scene_, o, eye_m, params_.face_px);
    }
    img.cost = params_.cost.of(img.object_segments, img.texels);
    images.push_back(std::move(img));
    const auto& changed = last_tick_.changed_memories;
    after.push_back(std::find(changed.begin(), changed.end(), m) != changed.end() ? changed : std::vector<int>{});
  }
  memories_.request(std::move(images), after);
  return last_tick_;
}

}  // namespace latsim::arp
