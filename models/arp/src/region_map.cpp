#include "latsim/arp/region_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace latsim::arp {

using renderer::RegionGrid;
using renderer::RegionIndex;

RegionMemoryMap::RegionMemoryMap(const RegionGrid& grid, std::vector<int> outer_rings)
    : grid_(grid), outer_rings_(std::move(outer_rings)), memory_of_(static_cast<size_t>(grid.region_count()), 0) {
  for (size_t i = 0; i < outer_rings_.size(); ++i) {
    if (outer_rings_[i] < 0 || (i > 0 && outer_rings_[i] <= outer_rings_[i - 1])) {
      throw std::invalid_argument("region memory map: outer rings must be >= 0 and strictly increasing");
    }
  }
  regions_.resize(outer_rings_.size() + 1);
}

int RegionMemoryMap::memory_of_ring(int ring) const {
  for (size_t i = 0; i < outer_rings_.size(); ++i) {
    if (ring <= outer_rings_[i]) return static_cast<int>(i);
  }
  return static_cast<int>(outer_rings_.size());
}

std::vector<int> RegionMemoryMap::set_home(RegionIndex home) {
  if (!grid_.contains(home)) throw std::out_of_range("region memory map: home region outside the grid");
  std::vector<std::vector<int>> lists(regions_.size());
  for (int id = 0; id < grid_.region_count(); ++id) {
    const RegionIndex r = grid_.from_linear(id);
    const int ring = std::max(std::abs(r.ix - home.ix), std::abs(r.iz - home.iz));
    const int m = memory_of_ring(ring);
    memory_of_[static_cast<size_t>(id)] = m;
    lists[static_cast<size_t>(m)].push_back(id);
  }
  std::vector<int> changed;
  for (size_t m = 0; m < lists.size(); ++m) {
    if (lists[m] != regions_[m] || home_.ix < 0) changed.push_back(static_cast<int>(m));
  }
  regions_ = std::move(lists);
  home_ = home;
  return changed;
}

double RegionMemoryMap::distance_to_region_m(int linear_region, const glm::dvec3& p) const {
  const renderer::Aabb box = grid_.region_bounds(grid_.from_linear(linear_region));
  const double dx = std::max({box.min_m.x - p.x, 0.0, p.x - box.max_m.x});
  const double dz = std::max({box.min_m.z - p.z, 0.0, p.z - box.max_m.z});
  return std::hypot(dx, dz);
}

double RegionMemoryMap::nearest_distance_m(int memory, const glm::dvec3& point_m) const {
  double best = std::numeric_limits<double>::infinity();
  for (int id : regions_of_memory(memory)) best = std::min(best, distance_to_region_m(id, point_m));
  return best;
}

bool RegionMemoryMap::is_partition() const {
  std::vector<int> seen(static_cast<size_t>(grid_.region_count()), 0);
  for (size_t m = 0; m < regions_.size(); ++m) {
    for (int id : regions_[m]) {
      if (id < 0 || id >= grid_.region_count()) return false;
      if (memory_of_[static_cast<size_t>(id)] != static_cast<int>(m)) return false;
      ++seen[static_cast<size_t>(id)];
    }
  }
  return std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; });
}

HomeRegionTracker::HomeRegionTracker(const RegionGrid& grid, double margin_m) : grid_(grid), margin_m_(margin_m) {
  if (!(margin_m >= 0.0) || !(2.0 * margin_m < grid.region_size_m())) {
    throw std::invalid_argument("home region tracker: the swap margin must lie in [0, region size / 2)");
  }
}

RegionIndex HomeRegionTracker::clamped_region(const glm::dvec3& point_m) const {
  const RegionIndex r = grid_.region_of(point_m);
  return {std::clamp(r.ix, 0, grid_.count_x() - 1), std::clamp(r.iz, 0, grid_.count_z() - 1)};
}

bool HomeRegionTracker::wants_swap(RegionIndex home, const glm::dvec3& user_m, RegionIndex& target) const {
  const RegionIndex here = clamped_region(user_m);
  if (here == home) return false;
  // Each axis follows the user only once the user is past that axis's
  // boundary by the margin; grid edges count as infinitely deep so a user who
  // walks off the grid still belongs to the edge region. Walking along a
  // boundary of the other axis does not hold the swap back.
  const renderer::Aabb box = grid_.region_bounds(here);
  const double inf = std::numeric_limits<double>::infinity();
  const double depth_x = std::min(here.ix > 0 ? user_m.x - box.min_m.x : inf,
                                  here.ix < grid_.count_x() - 1 ? box.max_m.x - user_m.x : inf);
  const double depth_z = std::min(here.iz > 0 ? user_m.z - box.min_m.z : inf,
                                  here.iz < grid_.count_z() - 1 ? box.max_m.z - user_m.z : inf);
  RegionIndex next = home;
  if (here.ix != home.ix && depth_x >= margin_m_) next.ix = here.ix;
  if (here.iz != home.iz && depth_z >= margin_m_) next.iz = here.iz;
  if (next == home) return false;
  target = next;
  return true;
}

}  // namespace latsim::arp
