// Region priority rendering as a running system: the decisions of the model,
// renders on a limited number of renderers, and what the display memories show.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "latsim/arp/display_memories.hpp"
#include "latsim/arp/memory_render_cost.hpp"
#include "latsim/arp/region_priority_model.hpp"
#include "latsim/arp/seam_meter.hpp"

namespace latsim::arp {

/// Settings of a region priority system.
struct RegionSystemParams {
  RegionPriorityParams model;
  MemoryRenderCost cost;
  int renderers = 1;
  int face_px = 256;  ///< cube memory resolution (covered texels)
};

/// Ticks a RegionPriorityModel, renders the updates it decides on a
/// DisplayMemories and tracks which memory shows each segment.
///
/// Presentation order: memories whose segments change in a swap (and every
/// memory's first image) are presented together, so each segment is in
/// exactly one shown image at every instant; with warping, an image is
/// presented no earlier than the slower memories' images its edges were
/// warped towards.
class RegionPrioritySystem {
 public:
  RegionPrioritySystem(des::Simulator& sim, des::KindId render_kind, const SegmentedScene& scene,
                       const renderer::RegionGrid& grid, RegionSystemParams params);

  /// One update opportunity: the model decides with the user at eye_m, and
  /// the decided images, drawn from eye_m (tracker sample tag `sample`), are requested.
  const RegionTick& tick(des::Time now, const glm::dvec3& eye_m, int64_t sample);
  /// Called with every batch of images presented together, after the shown state is updated.
  void on_present(DisplayMemories::PresentFn fn) { present_fn_ = std::move(fn); }

  const RegionPriorityModel& model() const { return model_; }
  const DisplayMemories& memories() const { return memories_; }
  const RegionSystemParams& params() const { return params_; }
  /// What the memories show now.
  ShownRegions shown() const;

 private:
  MemoryImage image_of(int memory, const std::vector<uint32_t>& segments, const glm::dvec3& eye_m, int64_t sample,
                       const std::shared_ptr<const RegionView>& view) const;
  void presented(const std::vector<const MemoryImage*>& batch);

  RegionSystemParams params_;
  RegionPriorityModel model_;
  DisplayMemories memories_;
  RegionTick last_tick_;
  std::vector<int> shown_memory_of_segment_;
  DisplayMemories::PresentFn present_fn_;
};

}  // namespace latsim::arp
