// Pinhole camera: pixel rays and the projection of world points to pixels.
#pragma once

#include <glm/gtc/quaternion.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>

#include "latsim/tracker/pose.hpp"

namespace latsim::renderer {

/// Maps between pixels and viewing directions of a pinhole camera with square pixels.
///
/// Continuous pixel coordinates put pixel (x, y)'s centre at (x + 0.5, y + 0.5); the image
/// covers [0, width) x [0, height), row 0 at the top, so floor() of a projected point gives
/// the pixel it lands in.
class Camera {
 public:
  /// Throws std::invalid_argument unless 0 < hfov_deg < 180 and both sizes are positive.
  Camera(double hfov_deg, int width_px, int height_px);

  int width_px() const { return width_px_; }
  int height_px() const { return height_px_; }
  double hfov_deg() const { return hfov_deg_; }
  double vfov_deg() const;
  /// Distance of the image plane in pixels (pixels per unit tangent).
  double focal_px() const { return focal_px_; }

  /// Unit direction in the head frame through continuous pixel coordinates (px, py).
  glm::dvec3 head_direction(double px, double py) const;
  /// Unit world direction through continuous pixel coordinates for this orientation.
  glm::dvec3 ray_direction(double px, double py, const glm::dquat& orientation) const;
  /// Unit world direction through the centre of pixel (x, y).
  glm::dvec3 pixel_ray(int x, int y, const glm::dquat& orientation) const;
  /// Continuous pixel coordinates of a world point seen from the pose; empty when the point
  /// is not in front of the eye. The result may lie outside the image.
  std::optional<glm::dvec2> project(const glm::dvec3& point_m, const tracker::Pose& pose) const;

 private:
  double hfov_deg_;
  int width_px_;
  int height_px_;
  double focal_px_;
};

}  // namespace latsim::renderer
