// Pinhole projection of world directions onto the HMD screen, for measuring
// gaps in pixels.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace latsim::arp {

/// The HMD screen as a pinhole camera with square pixels, looking down the
/// head's -z axis (x right, y up; pixel rows grow downwards).
class ScreenProjection {
 public:
  ScreenProjection(double hfov_deg, int width_px, int height_px);
  /// Pixel position of a world direction seen with head orientation `head`;
  /// false when it lies behind the eye or outside the screen.
  bool project(const glm::dquat& head, const glm::dvec3& direction_world, glm::dvec2& pixel) const;
  double focal_px() const { return focal_px_; }
  int width_px() const { return width_px_; }
  int height_px() const { return height_px_; }

 private:
  double focal_px_;
  int width_px_;
  int height_px_;
};

}  // namespace latsim::arp
