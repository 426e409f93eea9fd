#include "latsim/arp/region_priority_system.hpp"

#include <algorithm>

#include "latsim/arp/covered_texels.hpp"

namespace latsim::arp {

RegionPrioritySystem::RegionPrioritySystem(des::Simulator& sim, des::KindId render_kind, const SegmentedScene& scene,
                                           const renderer::RegionGrid& grid, RegionSystemParams params)
    : params_(std::move(params)),
      model_(scene, grid, params_.model),
      memories_(sim, render_kind, params_.renderers, model_.memory_count()),
      shown_memory_of_segment_(scene.segments.size(), -1) {
  memories_.on_present([this](const std::vector<const MemoryImage*>& batch) { presented(batch); });
}

MemoryImage RegionPrioritySystem::image_of(int memory, const std::vector<uint32_t>& segments,
                                           const glm::dvec3& eye_m, int64_t sample,
                                           const std::shared_ptr<const RegionView>& view) const {
  const SegmentedScene& scene = model_.scene();
  MemoryImage img;
  img.memory = memory;
  img.contents = segments;
  img.eye_m = eye_m;
  img.sample = sample;
  img.view = view;
  for (uint32_t s : segments) {
    img.object_segments += scene.segments[s].object_segments;
    // Covered texels of the unwarped geometry: warping moves vertices by centimetres.
    if (params_.cost.counts_pixels())
      img.texels += object_texels(scene.scene, scene.segments[s].scene_object, eye_m, params_.face_px);
  }
  // A whole object is the geometry of the segments it would be cut into and costs as many.
  img.cost = params_.cost.of(img.object_segments, img.texels);
  return img;
}

const RegionTick& RegionPrioritySystem::tick(des::Time now, const glm::dvec3& eye_m, int64_t sample) {
  last_tick_ = model_.tick(now, eye_m);
  if (last_tick_.updated.empty()) return last_tick_;
  const auto view = std::make_shared<const RegionView>(model_.view());
  const auto lists = model_.segments_per_memory();
  const int count = model_.memory_count();
  std::vector<MemoryImage> images;
  std::vector<std::vector<int>> after;
  // Request order fastest first: the queue serves memories fastest first anyway.
  for (auto it = last_tick_.updated.rbegin(); it != last_tick_.updated.rend(); ++it) {
    const int m = *it;
    images.push_back(image_of(m, lists[static_cast<size_t>(m)], eye_m, sample, view));
    std::vector<int> deps;
    if (std::find(last_tick_.changed.begin(), last_tick_.changed.end(), m) != last_tick_.changed.end())
      deps = last_tick_.changed;
    if (params_.model.warping) {
      for (int s = m + 1; s < count; ++s) deps.push_back(s);
    }
    after.push_back(std::move(deps));
  }
  memories_.request(std::move(images), after);
  return last_tick_;
}

void RegionPrioritySystem::presented(const std::vector<const MemoryImage*>& batch) {
  // Only the newest image of each memory in the batch is shown. Segments
  // leave the images replaced before any enters, so a segment moving between
  // two memories of the batch ends up in its new one.
  std::vector<const MemoryImage*> newest(static_cast<size_t>(model_.memory_count()), nullptr);
  for (const MemoryImage* img : batch) newest[static_cast<size_t>(img->memory)] = img;
  for (int& m : shown_memory_of_segment_) {
    if (m >= 0 && newest[static_cast<size_t>(m)]) m = -1;
  }
  for (const MemoryImage* img : newest) {
    if (!img) continue;
    for (uint32_t s : img->contents) shown_memory_of_segment_[s] = img->memory;
  }
  if (present_fn_) present_fn_(batch);
}

ShownRegions RegionPrioritySystem::shown() const {
  ShownRegions out;
  for (int m = 0; m < model_.memory_count(); ++m) {
    const MemoryImage* img = memories_.shown(m);
    out.views.push_back(img ? img->view.get() : nullptr);
  }
  out.memory_of_segment = shown_memory_of_segment_;
  return out;
}

}  // namespace latsim::arp
