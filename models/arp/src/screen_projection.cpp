#include "latsim/arp/screen_projection.hpp"
#include "latsim/units/units.hpp"

#include <cmath>
#include <stdexcept>

namespace latsim::arp {

ScreenProjection::ScreenProjection(double hfov_deg, int width_px, int height_px)
    : focal_px_(0.0), width_px_(width_px), height_px_(height_px) {
  if (!(hfov_deg > 0.0 && hfov_deg < 180.0) || width_px <= 0 || height_px <= 0) {
    throw std::invalid_argument("screen projection: need 0 < hfov_deg < 180 and a positive size");
  }
  focal_px_ = 0.5 * width_px / std::tan(units::deg_to_rad(0.5 * hfov_deg));
}

bool ScreenProjection::project(const glm::dquat& head, const glm::dvec3& direction_world, glm::dvec2& pixel) const {
  const glm::dvec3 d = glm::conjugate(head) * direction_world;
  if (!(d.z < 0.0)) return false;
  pixel.x = 0.5 * width_px_ + focal_px_ * d.x / -d.z;
  pixel.y = 0.5 * height_px_ - focal_px_ * d.y / -d.z;
  return pixel.x >= 0.0 && pixel.x <= width_px_ && pixel.y >= 0.0 && pixel.y <= height_px_;
}

}  // namespace latsim::arp
