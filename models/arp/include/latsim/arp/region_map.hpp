// Which display memory holds which region: rings around the user's home
// region, the fastest memory holding the home neighbourhood.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "latsim/renderer/region_grid.hpp"

namespace latsim::arp {

/// Maps regions to memories by their ring (Chebyshev distance in regions) from
/// a home region: memory i holds the rings up to outer_ring[i] not held by a
/// faster memory; the slowest memory holds everything further out.
class RegionMemoryMap {
 public:
  /// `outer_rings` has memory_count - 1 strictly increasing entries >= 0.
  RegionMemoryMap(const renderer::RegionGrid& grid, std::vector<int> outer_rings);

  int memory_count() const { return static_cast<int>(outer_rings_.size()) + 1; }
  const renderer::RegionGrid& grid() const { return grid_; }
  renderer::RegionIndex home() const { return home_; }
  /// Re-maps every region around a new home region. Returns the memories whose
  /// set of regions changed (ascending).
  std::vector<int> set_home(renderer::RegionIndex home);

  int memory_of_region(int linear_region) const { return memory_of_.at(static_cast<size_t>(linear_region)); }
  const std::vector<int>& regions_of_memory(int memory) const { return regions_.at(static_cast<size_t>(memory)); }
  /// The memory a ring lands in.
  int memory_of_ring(int ring) const;
  /// Horizontal distance from a point to the nearest region of the memory
  /// (0 inside one; infinity when the memory holds no region).
  double nearest_distance_m(int memory, const glm::dvec3& point_m) const;
  /// Horizontal distance from a point to a region's square (0 inside).
  double distance_to_region_m(int linear_region, const glm::dvec3& point_m) const;
  /// True when every grid region appears in exactly one memory's list and the
  /// lists agree with memory_of_region (the invariant tests check at every tick).
  bool is_partition() const;

 private:
  renderer::RegionGrid grid_;
  std::vector<int> outer_rings_;
  renderer::RegionIndex home_{-1, -1};
  std::vector<int> memory_of_;
  std::vector<std::vector<int>> regions_;
};

/// Decides when the home region may change: along each axis, only once the
/// user is past the crossed boundary by at least the margin, so a path along
/// a boundary never makes the home region flip back and forth.
class HomeRegionTracker {
 public:
  HomeRegionTracker(const renderer::RegionGrid& grid, double margin_m);
  /// The home region the user has moved into by the margin, if it differs from `home`.
  bool wants_swap(renderer::RegionIndex home, const glm::dvec3& user_m, renderer::RegionIndex& target) const;
  /// Grid region of a point, clamped onto the grid.
  renderer::RegionIndex clamped_region(const glm::dvec3& point_m) const;

 private:
  renderer::RegionGrid grid_;
  double margin_m_;
};

}  // namespace latsim::arp
