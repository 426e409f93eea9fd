#include "latsim/measurement/shown_trace.hpp"
#include "latsim/units/units.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace latsim::measurement {

ShownTrace::ShownTrace(ScreenPoint point, int width_px, int lines)
    : line_(std::clamp(static_cast<int>(std::floor(point.y * lines)), 0, std::max(0, lines - 1))),
      column_(std::clamp(static_cast<int>(std::floor(point.x * width_px)), 0, std::max(0, width_px - 1))) {}

const std::vector<ShownSample>& ShownTrace::sorted() {
  std::stable_sort(samples_.begin(), samples_.end(),
                   [](const ShownSample& a, const ShownSample& b) { return a.photon < b.photon; });
  return samples_;
}

glm::dquat controller_seen(const glm::dquat& true_head, const glm::dquat& shown_head, const glm::dquat& drawn) {
  return glm::normalize(true_head * glm::inverse(shown_head) * drawn);
}

double twist_deg(const glm::dquat& from, const glm::dquat& to, const glm::dvec3& axis) {
  glm::dquat r = to * glm::inverse(from);
  if (r.w < 0.0) r = -r;  // the short way round
  const double along = r.x * axis.x + r.y * axis.y + r.z * axis.z;
  return units::rad_to_deg(2.0 * std::atan2(along, r.w));
}

}  // namespace latsim::measurement
