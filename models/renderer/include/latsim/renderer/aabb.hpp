// Axis-aligned bounding boxes in world metres.
#pragma once

#include <glm/vec3.hpp>
#include <glm/common.hpp>

#include <limits>

namespace latsim::renderer {

/// An axis-aligned box, empty until a point is added (min > max on every axis).
struct Aabb {
  glm::dvec3 min_m{std::numeric_limits<double>::infinity()};
  glm::dvec3 max_m{-std::numeric_limits<double>::infinity()};

  bool empty() const { return min_m.x > max_m.x || min_m.y > max_m.y || min_m.z > max_m.z; }
  void extend(const glm::dvec3& point_m) {
    min_m = glm::min(min_m, point_m);
    max_m = glm::max(max_m, point_m);
  }
  void extend(const Aabb& other) {
    if (other.empty()) return;
    extend(other.min_m);
    extend(other.max_m);
  }
  glm::dvec3 centre_m() const { return 0.5 * (min_m + max_m); }
  glm::dvec3 size_m() const { return max_m - min_m; }
  /// Closed-interval overlap, so boxes that only touch count as overlapping.
  bool overlaps(const Aabb& other) const {
    return !empty() && !other.empty() && min_m.x <= other.max_m.x && other.min_m.x <= max_m.x &&
           min_m.y <= other.max_m.y && other.min_m.y <= max_m.y && min_m.z <= other.max_m.z &&
           other.min_m.z <= max_m.z;
  }
};

}  // namespace latsim::renderer
