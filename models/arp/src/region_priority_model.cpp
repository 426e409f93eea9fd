#include "latsim/arp/region_priority_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "latsim/arp/validity.hpp"
#include "latsim/units/units.hpp"

namespace latsim::arp {

RegionPriorityModel::RegionPriorityModel(const SegmentedScene& scene, const renderer::RegionGrid& grid,
                                         RegionPriorityParams params)
    : scene_(scene),
      params_(params),
      map_(grid, params.outer_rings),
      home_tracker_(grid, params.swap_margin_m),
      memories_(static_cast<size_t>(map_.memory_count())),
      memory_of_segment_(scene.segments.size(), 0) {
  if (!(params.warp_falloff_m >= 0.0)) throw std::invalid_argument("region priority: warp falloff must be >= 0");
  // Validates the angle once, so ticks cannot fail on it.
  translational_validity_distance_m(1.0, params.threshold_rad);
  for (const Segment& seg : scene_.segments) any_animated_ = any_animated_ || seg.animated;
  view_.eyes_m.assign(memories_.size(), glm::dvec3(0.0));
  view_.drawn.assign(memories_.size(), 0);
}

void RegionPriorityModel::assign_segments() {
  for (size_t s = 0; s < scene_.segments.size(); ++s) {
    const Segment& seg = scene_.segments[s];
    // An uncut object spanning several regions must be as fresh as its nearest part.
    int m = map_.memory_count() - 1;
    for (int r : seg.regions) m = std::min(m, map_.memory_of_region(r));
    memory_of_segment_[s] = seg.animated ? 0 : m;
  }
}

std::vector<std::vector<uint32_t>> RegionPriorityModel::segments_per_memory() const {
  std::vector<std::vector<uint32_t>> lists(static_cast<size_t>(map_.memory_count()));
  for (size_t s = 0; s < memory_of_segment_.size(); ++s) {
    lists[static_cast<size_t>(memory_of_segment_[s])].push_back(static_cast<uint32_t>(s));
  }
  return lists;
}

void RegionPriorityModel::draw(int memory, des::Time now, const glm::dvec3& eye_m) {
  RegionMemoryState& st = memories_[static_cast<size_t>(memory)];
  st.drawn = true;
  st.drawn_at = now;
  st.eye_m = eye_m;
  // The nearest region is the first to go invalid; an empty memory never needs redrawing.
  const double nearest = map_.nearest_distance_m(memory, eye_m);
  st.threshold_m = std::isfinite(nearest) ? translational_validity_distance_m(nearest, params_.threshold_rad)
                                          : std::numeric_limits<double>::infinity();
  ++st.updates;
  view_.eyes_m[static_cast<size_t>(memory)] = eye_m;
  view_.drawn[static_cast<size_t>(memory)] = 1;
}

RegionTick RegionPriorityModel::tick(des::Time now, const glm::dvec3& eye_m) {
  RegionTick result;
  const int count = map_.memory_count();
  std::vector<bool> update(static_cast<size_t>(count), false);
  if (!started_) {
    map_.set_home(home_tracker_.clamped_region(eye_m));
    assign_segments();
    started_ = true;
    // Every memory's first image changes what it holds (from nothing).
    for (int m = 0; m < count; ++m) result.changed.push_back(m);
  }
  for (int m = 0; m < count; ++m) {
    const RegionMemoryState& st = memories_[static_cast<size_t>(m)];
    update[static_cast<size_t>(m)] =
        !st.drawn || glm::length(eye_m - st.eye_m) > st.threshold_m || (m == 0 && any_animated_);
  }
  renderer::RegionIndex target;
  if (update[static_cast<size_t>(count - 1)] && home_tracker_.wants_swap(map_.home(), eye_m, target)) {
    const std::vector<int> before = memory_of_segment_;
    std::vector<bool> changed(static_cast<size_t>(count), false);
    for (int m : map_.set_home(target)) changed[static_cast<size_t>(m)] = true;
    assign_segments();
    for (size_t s = 0; s < before.size(); ++s) {
      if (before[s] == memory_of_segment_[s]) continue;
      changed[static_cast<size_t>(before[s])] = true;
      changed[static_cast<size_t>(memory_of_segment_[s])] = true;
    }
    for (int m = 0; m < count; ++m) {
      if (!changed[static_cast<size_t>(m)]) continue;
      update[static_cast<size_t>(m)] = true;
      result.changed.push_back(m);
    }
    ++swaps_;
    result.swapped = true;
  }
  if (params_.warping) {
    for (int m = count - 2; m >= 0; --m) {
      if (update[static_cast<size_t>(m + 1)]) update[static_cast<size_t>(m)] = true;
    }
  }
  // Slowest first, so a faster memory warps towards its slower neighbour's new viewpoint.
  for (int m = count - 1; m >= 0; --m) {
    if (!update[static_cast<size_t>(m)]) continue;
    draw(m, now, eye_m);
    result.updated.push_back(m);
  }
  view_.home = map_.home();
  return result;
}

int RegionPriorityModel::memory_of_region(int linear_region, renderer::RegionIndex home) const {
  const renderer::RegionIndex r = map_.grid().from_linear(linear_region);
  return map_.memory_of_ring(std::max(std::abs(r.ix - home.ix), std::abs(r.iz - home.iz)));
}

double RegionPriorityModel::warp_weight(double distance_m) const {
  if (distance_m <= 0.0) return 1.0;
  if (distance_m >= params_.warp_falloff_m) return 0.0;
  return 0.5 * (1.0 + std::cos(units::kPi * distance_m / params_.warp_falloff_m));
}

glm::dvec3 RegionPriorityModel::warp_offset_m(int memory, const glm::dvec3& vertex_m, const RegionView& view) const {
  if (!params_.warping || memory >= map_.memory_count() - 1) return glm::dvec3(0.0);
  const renderer::RegionGrid& grid = map_.grid();
  const renderer::RegionIndex centre = grid.region_of(vertex_m);
  const int reach = static_cast<int>(std::ceil(params_.warp_falloff_m / grid.region_size_m())) + 1;
  double best_distance = std::numeric_limits<double>::infinity();
  int slower = -1;
  for (int iz = centre.iz - reach; iz <= centre.iz + reach; ++iz) {
    for (int ix = centre.ix - reach; ix <= centre.ix + reach; ++ix) {
      if (!grid.contains({ix, iz})) continue;
      const int id = grid.linear_index({ix, iz});
      const int m = memory_of_region(id, view.home);
      if (m <= memory) continue;
      const double d = map_.distance_to_region_m(id, vertex_m);
      // Equal distances (a corner) go to the next slower memory, the one this memory borders.
      if (d < best_distance || (d == best_distance && m < slower)) {
        best_distance = d;
        slower = m;
      }
    }
  }
  const double w = slower < 0 ? 0.0 : warp_weight(best_distance);
  if (w == 0.0) return glm::dvec3(0.0);
  if (!view.drawn[static_cast<size_t>(memory)] || !view.drawn[static_cast<size_t>(slower)]) return glm::dvec3(0.0);
  // Drawn from eye(memory), v + (eye(memory) - eye(slower)) + slower's own offset
  // appears exactly where the slower memory shows v.
  return w * ((view.eyes_m[static_cast<size_t>(memory)] - view.eyes_m[static_cast<size_t>(slower)]) +
              warp_offset_m(slower, vertex_m, view));
}

glm::dvec3 RegionPriorityModel::drawn_direction(int memory, const glm::dvec3& vertex_m, const RegionView& view) const {
  return vertex_m + warp_offset_m(memory, vertex_m, view) - view.eyes_m.at(static_cast<size_t>(memory));
}

}  // namespace latsim::arp
