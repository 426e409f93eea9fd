// Column regions of the world for region priority rendering.
#pragma once

#include "latsim/renderer/aabb.hpp"
#include "latsim/renderer/scene.hpp"

#include <glm/vec3.hpp>

#include <compare>
#include <cstdint>
#include <vector>

namespace latsim::renderer {

/// Column and row of a region on the x-z plane.
struct RegionIndex {
  int ix = 0;
  int iz = 0;
  auto operator<=>(const RegionIndex&) const = default;
};

/// Cuts the world into square-based columns spanning its full height (y up). Region
/// (ix, iz) covers the half-open x interval [origin_x + ix*size, origin_x + (ix+1)*size)
/// and likewise in z, so a point on a boundary belongs to the region after it.
class RegionGrid {
 public:
  /// Grid whose origin is world_bounds.min_m (x, z) and which covers world_bounds with
  /// whole regions. Throws std::invalid_argument for an empty box or non-positive size.
  RegionGrid(const Aabb& world_bounds, double region_size_m);

  int count_x() const { return count_x_; }
  int count_z() const { return count_z_; }
  int region_count() const { return count_x_ * count_z_; }
  double region_size_m() const { return region_size_m_; }

  /// Region containing the point, not clamped (may lie outside the grid; a point on the
  /// far world boundary gets index count, one past the last region).
  RegionIndex region_of(const glm::dvec3& point_m) const;
  bool contains(RegionIndex region) const;
  /// Row-major index iz * count_x + ix; throws std::out_of_range outside the grid.
  int linear_index(RegionIndex region) const;
  RegionIndex from_linear(int index) const;
  /// The column of a region, y spanning the world bounds.
  Aabb region_bounds(RegionIndex region) const;
  /// Grid regions whose columns overlap the box (ix fastest). An extent that ends exactly
  /// on an inner boundary does not reach into the next region; geometry on the far world
  /// boundary belongs to the last region; a box outside the grid gives none.
  std::vector<RegionIndex> regions_of(const Aabb& box) const;
  /// For every region (by linear index), the ids of the scene objects whose bounds overlap it.
  std::vector<std::vector<uint32_t>> objects_per_region(const Scene& scene) const;

 private:
  glm::dvec3 origin_m_;
  double top_y_m_;
  double region_size_m_;
  int count_x_;
  int count_z_;
};

}  // namespace latsim::renderer
