// What the seams between region memories look like on screen: tear gaps at
// vertices that neighbouring segments share, and the stretch that region
// warping puts into the triangles it moves.
#pragma once

#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "latsim/arp/region_priority_model.hpp"
#include "latsim/arp/screen_projection.hpp"
#include "latsim/renderer/ray_caster.hpp"

namespace latsim::arp {

/// What the display memories show at one instant.
struct ShownRegions {
  std::vector<const RegionView*> views;  ///< per memory: the view its image was drawn against (null: none yet)
  std::vector<int> memory_of_segment;    ///< per segment: the memory whose image holds it (-1: none)
};

/// A point inside a warped triangle: where it is, and where the warped image draws it.
struct WarpedPoint {
  glm::dvec3 true_m{0.0};
  glm::dvec3 drawn_m{0.0};
};

/// Measures tears and stretch as the user sees them, with the head at some
/// orientation and the user at some position: points off screen do not count,
/// nor (with an occluder) points hidden behind nearer geometry.
class SeamMeter {
 public:
  /// `occluder` (may be null: no occlusion test) holds the scene's geometry.
  SeamMeter(const RegionPriorityModel& model, const renderer::RayCaster* occluder);

  /// Pixel distance between the two drawings of every shared vertex whose
  /// segments are shown by different memories, both on screen, the vertex visible from eye_m.
  void tear_gaps_px(const ShownRegions& shown, const glm::dquat& head, const glm::dvec3& eye_m,
                    const ScreenProjection& screen, std::vector<double>& gaps) const;
  /// The centroids of the triangles of `segments` that warping moves in an
  /// image of `memory` drawn against `view` (a centroid is drawn at the mean
  /// of its corners' warped positions: triangles are rasterised between them).
  std::vector<WarpedPoint> warped_points(int memory, const std::vector<uint32_t>& segments,
                                         const RegionView& view) const;
  /// For every point on screen and visible from eye_m: pixel distance between
  /// where an image drawn from image_eye_m shows it and where an unwarped
  /// render from eye_m would.
  void stretch_px(const std::vector<WarpedPoint>& points, const glm::dvec3& image_eye_m, const glm::dquat& head,
                  const glm::dvec3& eye_m, const ScreenProjection& screen, std::vector<double>& stretch) const;
  /// True without an occluder, or when nothing nearer than the point lies on the ray from eye_m to it.
  bool visible(const glm::dvec3& point_m, const glm::dvec3& eye_m) const;

 private:
  const RegionPriorityModel& model_;
  const renderer::RayCaster* occluder_;
};

}  // namespace latsim::arp
