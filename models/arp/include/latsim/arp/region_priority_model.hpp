// Region priority rendering: regions in memories by their ring around the
// user, on-demand memory updates by translation threshold, region swapping
// with a margin, and region warping.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "latsim/arp/region_map.hpp"
#include "latsim/arp/segmentation.hpp"
#include "latsim/des/time.hpp"

namespace latsim::arp {

/// Settings of region priority rendering.
struct RegionPriorityParams {
  std::vector<int> outer_rings{1, 2, 4};  ///< memory_count - 1 ring limits
  double threshold_rad = 0.003;           ///< the angle an image may be off before it is redrawn
  double swap_margin_m = 0.25;            ///< how far inside a new region the user must be
  bool warping = false;
  double warp_falloff_m = 1.0;            ///< distance over which the warp fades out
};

/// One display memory's last drawing as decided (its image may still be in the renderer).
struct RegionMemoryState {
  bool drawn = false;
  des::Time drawn_at;
  glm::dvec3 eye_m{0.0};          ///< the user position it was drawn from
  double threshold_m = 0.0;       ///< how far the user may move before it asks to be redrawn
  int64_t updates = 0;            ///< updates decided
};

/// What an image of a display memory was drawn against: the home region and
/// every memory's viewpoint at the moment its update was decided. Warped
/// vertices depend on the slower memories' viewpoints, so a shown image is
/// only reproducible from its own view.
struct RegionView {
  renderer::RegionIndex home{-1, -1};
  std::vector<glm::dvec3> eyes_m;
  std::vector<char> drawn;
};

/// What one tick decided.
struct RegionTick {
  std::vector<int> updated;   ///< memories to redraw, slowest first
  std::vector<int> changed;   ///< memories whose set of segments changed (a swap), ascending
  bool swapped = false;
};

/// The state machine of region priority rendering, ticked at the maximum update rate.
class RegionPriorityModel {
 public:
  RegionPriorityModel(const SegmentedScene& scene, const renderer::RegionGrid& grid, RegionPriorityParams params);

  /// One update opportunity at time `now` with the user at `eye_m`: memories
  /// ask for an update when the user has moved beyond their threshold; at the
  /// slowest memory's request the home region may swap (memories whose
  /// segments change are redrawn together); with warping, a redrawn memory
  /// makes every faster one redraw too (their edges follow it).
  RegionTick tick(des::Time now, const glm::dvec3& eye_m);

  int memory_count() const { return map_.memory_count(); }
  const RegionMemoryMap& map() const { return map_; }
  const std::vector<RegionMemoryState>& memories() const { return memories_; }
  int memory_of_segment(size_t segment) const { return memory_of_segment_.at(segment); }
  const std::vector<int>& memory_of_segments() const { return memory_of_segment_; }
  std::vector<std::vector<uint32_t>> segments_per_memory() const;
  int64_t swaps() const { return swaps_; }
  const RegionPriorityParams& params() const { return params_; }
  const SegmentedScene& scene() const { return scene_; }
  /// The decided state as a view (what an update decided now is drawn against).
  const RegionView& view() const { return view_; }

  /// The memory a region belongs to when `home` is the home region.
  int memory_of_region(int linear_region, renderer::RegionIndex home) const;
  /// How far a vertex drawn by `memory` against `view` is moved by region
  /// warping (zero without warping): the perturbation towards the nearest
  /// slower memory, its own warp included, weighted by the falloff.
  glm::dvec3 warp_offset_m(int memory, const glm::dvec3& vertex_m, const RegionView& view) const;
  glm::dvec3 warp_offset_m(int memory, const glm::dvec3& vertex_m) const { return warp_offset_m(memory, vertex_m, view_); }
  /// The direction (not normalised) in which `memory`'s image drawn against `view` shows a vertex.
  glm::dvec3 drawn_direction(int memory, const glm::dvec3& vertex_m, const RegionView& view) const;
  /// Falloff weight of the warp at a distance from the edge: 1 at the edge,
  /// smoothly down to 0 at the falloff distance.
  double warp_weight(double distance_m) const;

 private:
  void assign_segments();
  void draw(int memory, des::Time now, const glm::dvec3& eye_m);

  const SegmentedScene& scene_;
  RegionPriorityParams params_;
  RegionMemoryMap map_;
  HomeRegionTracker home_tracker_;
  std::vector<RegionMemoryState> memories_;
  std::vector<int> memory_of_segment_;
  RegionView view_;
  bool started_ = false;
  bool any_animated_ = false;
  int64_t swaps_ = 0;
};

}  // namespace latsim::arp
