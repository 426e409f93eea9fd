// Pictures of display memories: cube maps of a memory's segments rendered
// from the viewpoint it was last drawn from, composed by depth and seen
// through the viewport mapping of a head orientation.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "latsim/arp/display_memories.hpp"
#include "latsim/arp/region_priority_model.hpp"
#include "latsim/renderer/camera.hpp"
#include "latsim/renderer/cube_map.hpp"
#include "latsim/renderer/image.hpp"
#include "latsim/renderer/ray_caster.hpp"

namespace latsim::arp {

/// The HMD image of a set of cube memories: per pixel, the direction of the
/// head orientation is looked up in every cube and the nearest surface wins.
renderer::Frame view_through_cubes(std::span<const renderer::CubeMap* const> cubes, const renderer::Camera& camera,
                                   const glm::dquat& orientation, const glm::vec3& background);

/// Renders the cube memories of region priority rendering as they are shown:
/// memory m holds the segments of its shown image, warped (when the model
/// warps) against the image's own view, seen from the image's position.
class MemoryRenderer {
 public:
  MemoryRenderer(const SegmentedScene& scene, int face_px, glm::vec3 background, int thread_count);
  /// One cube per memory; a memory that shows nothing yet is empty.
  std::vector<renderer::CubeMap> render(const RegionPriorityModel& model,
                                        const std::vector<const MemoryImage*>& shown) const;
  /// A single cube of the whole scene from one point (plain address recalculation).
  renderer::CubeMap render_all(const glm::dvec3& eye_m) const;

 private:
  renderer::CubeMap render_memory(const RegionPriorityModel& model, const MemoryImage& image) const;

  const SegmentedScene& scene_;
  int face_px_;
  glm::vec3 background_;
  int thread_count_;
  std::unique_ptr<renderer::RayCaster> caster_;
};

/// A square crop of an image around a pixel, enlarged by an integer factor.
renderer::ImageRGB close_up(const renderer::ImageRGB& image, int centre_x, int centre_y, int half_size_px, int factor);

}  // namespace latsim::arp
