#include "latsim/renderer/camera.hpp"
#include "latsim/units/units.hpp"

#include <glm/geometric.hpp>

#include <cmath>
#include <stdexcept>
#include <string>

namespace latsim::renderer {

Camera::Camera(double hfov_deg, int width_px, int height_px)
    : hfov_deg_(hfov_deg), width_px_(width_px), height_px_(height_px), focal_px_(0.0) {
  if (!(hfov_deg > 0.0 && hfov_deg < 180.0)) {
    throw std::invalid_argument("camera: hfov_deg must be in (0, 180), got " + std::to_string(hfov_deg));
  }
  if (width_px <= 0 || height_px <= 0) {
    throw std::invalid_argument("camera: width and height must be positive, got " +
                                std::to_string(width_px) + " x " + std::to_string(height_px));
  }
  const double half_fov_rad = units::deg_to_rad(0.5 * hfov_deg);
  focal_px_ = 0.5 * width_px / std::tan(half_fov_rad);
}

double Camera::vfov_deg() const {
  return units::rad_to_deg(2.0 * std::atan(0.5 * height_px_ / focal_px_));
}

glm::dvec3 Camera::head_direction(double px, double py) const {
  // Image y grows downwards while head-frame y grows upwards, hence the sign flip.
  const glm::dvec3 d((px - 0.5 * width_px_) / focal_px_, (0.5 * height_px_ - py) / focal_px_, -1.0);
  return glm::normalize(d);
}

glm::dvec3 Camera::ray_direction(double px, double py, const glm::dquat& orientation) const {
  return glm::normalize(orientation * head_direction(px, py));
}

glm::dvec3 Camera::pixel_ray(int x, int y, const glm::dquat& orientation) const {
  return ray_direction(x + 0.5, y + 0.5, orientation);
}

std::optional<glm::dvec2> Camera::project(const glm::dvec3& point_m, const tracker::Pose& pose) const {
  // Into the head frame: the inverse of a unit quaternion is its conjugate; normalising
  // guards against poses whose quaternion has drifted from unit length.
  const glm::dquat to_head = glm::conjugate(glm::normalize(pose.orientation));
  const glm::dvec3 d = to_head * (point_m - pose.position_m);
  if (!(d.z < 0.0)) return std::nullopt;
  const double depth = -d.z;
  return glm::dvec2(0.5 * width_px_ + focal_px_ * d.x / depth, 0.5 * height_px_ - focal_px_ * d.y / depth);
}

}  // namespace latsim::renderer
