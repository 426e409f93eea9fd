#include "latsim/renderer/region_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace latsim::renderer {
namespace {

int cover_count(double extent_m, double size_m) {
  // A world exactly n regions wide has n regions, not n + 1 for its far boundary.
  return std::max(1, static_cast<int>(std::ceil(extent_m / size_m)));
}

// Index range [first, last] of cells a closed interval [lo, hi] reaches into, with cells
// half-open, before clamping.
std::pair<int, int> cell_range(double lo, double hi, double origin, double size) {
  const int first = static_cast<int>(std::floor((lo - origin) / size));
  const int last = static_cast<int>(std::ceil((hi - origin) / size)) - 1;
  return {first, std::max(first, last)};
}

}  // namespace

RegionGrid::RegionGrid(const Aabb& world_bounds, double region_size_m)
    : origin_m_(world_bounds.min_m),
      top_y_m_(world_bounds.max_m.y),
      region_size_m_(region_size_m),
      count_x_(1),
      count_z_(1) {
  if (world_bounds.empty()) throw std::invalid_argument("region grid: world bounds are empty");
  if (!(region_size_m > 0.0) || !std::isfinite(region_size_m)) {
    throw std::invalid_argument("region grid: region_size_m must be positive, got " +
                                std::to_string(region_size_m));
  }
  count_x_ = cover_count(world_bounds.max_m.x - origin_m_.x, region_size_m);
  count_z_ = cover_count(world_bounds.max_m.z - origin_m_.z, region_size_m);
}

RegionIndex RegionGrid::region_of(const glm::dvec3& point_m) const {
  return {static_cast<int>(std::floor((point_m.x - origin_m_.x) / region_size_m_)),
          static_cast<int>(std::floor((point_m.z - origin_m_.z) / region_size_m_))};
}

bool RegionGrid::contains(RegionIndex region) const {
  return region.ix >= 0 && region.ix < count_x_ && region.iz >= 0 && region.iz < count_z_;
}

int RegionGrid::linear_index(RegionIndex region) const {
  if (!contains(region)) {
    throw std::out_of_range("region grid: region (" + std::to_string(region.ix) + ", " +
                            std::to_string(region.iz) + ") is outside the " +
                            std::to_string(count_x_) + " x " + std::to_string(count_z_) + " grid");
  }
  return region.iz * count_x_ + region.ix;
}

RegionIndex RegionGrid::from_linear(int index) const {
  if (index < 0 || index >= region_count()) {
    throw std::out_of_range("region grid: linear index " + std::to_string(index) + " out of range");
  }
  return {index % count_x_, index / count_x_};
}

Aabb RegionGrid::region_bounds(RegionIndex region) const {
  Aabb box;
  box.min_m = {origin_m_.x + region.ix * region_size_m_, origin_m_.y,
               origin_m_.z + region.iz * region_size_m_};
  box.max_m = {origin_m_.x + (region.ix + 1) * region_size_m_, top_y_m_,
               origin_m_.z + (region.iz + 1) * region_size_m_};
  return box;
}

std::vector<RegionIndex> RegionGrid::regions_of(const Aabb& box) const {
  std::vector<RegionIndex> regions;
  if (box.empty()) return regions;
  // The grid is closed on its far side: geometry lying on the far world boundary (a wall
  // at x = max) belongs to the last region instead of to none.
  const double end_x = origin_m_.x + count_x_ * region_size_m_;
  const double end_z = origin_m_.z + count_z_ * region_size_m_;
  if (box.max_m.x < origin_m_.x || box.max_m.z < origin_m_.z || box.min_m.x > end_x || box.min_m.z > end_z) {
    return regions;
  }
  auto [x0, x1] = cell_range(box.min_m.x, box.max_m.x, origin_m_.x, region_size_m_);
  auto [z0, z1] = cell_range(box.min_m.z, box.max_m.z, origin_m_.z, region_size_m_);
  x0 = std::clamp(x0, 0, count_x_ - 1);
  z0 = std::clamp(z0, 0, count_z_ - 1);
  x1 = std::clamp(x1, x0, count_x_ - 1);
  z1 = std::clamp(z1, z0, count_z_ - 1);
  for (int iz = z0; iz <= z1; ++iz) {
    for (int ix = x0; ix <= x1; ++ix) regions.push_back({ix, iz});
  }
  return regions;
}

std::vector<std::vector<uint32_t>> RegionGrid::objects_per_region(const Scene& scene) const {
  std::vector<std::vector<uint32_t>> lists(static_cast<size_t>(region_count()));
  for (uint32_t id = 0; id < scene.object_count(); ++id) {
    for (RegionIndex region : regions_of(scene.objects()[id].bounds)) {
      lists[static_cast<size_t>(linear_index(region))].push_back(id);
    }
  }
  return lists;
}

}  // namespace latsim::renderer
