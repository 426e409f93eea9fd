#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "latsim/tracker/motion_source.hpp"

namespace latsim::tracker {

PolylineWalk::PolylineWalk(WalkParams params) : params_(std::move(params)) {
  if (params_.points_m.empty()) throw std::invalid_argument("a walk needs at least one point");
  if (!(params_.speed_m_s > 0.0) || !std::isfinite(params_.speed_m_s))
    throw std::invalid_argument("walking speed must be positive and finite");

  std::vector<glm::dvec3> corners = params_.points_m;
  if (params_.loop) corners.push_back(corners.front());

  // Heading of the first horizontal segment, used for any vertical segment
  // before it (a pure climb has no horizontal direction to face).
  glm::dquat facing = params_.orientation;
  for (size_t i = 0; i + 1 < corners.size(); ++i) {
    const glm::dvec3 d = corners[i + 1] - corners[i];
    if (d.x != 0.0 || d.z != 0.0) {
      facing = quat_from_yaw_pitch(std::atan2(-d.x, -d.z), 0.0);
      break;
    }
  }

  for (size_t i = 0; i + 1 < corners.size(); ++i) {
    const glm::dvec3 d = corners[i + 1] - corners[i];
    const double length_m = glm::length(d);
    if (!std::isfinite(length_m)) throw std::invalid_argument("walk points must be finite");
    if (length_m == 0.0) continue;  // repeated points add nothing to the path
    // Facing uses the horizontal direction only: walkers look level.
    if (d.x != 0.0 || d.z != 0.0) facing = quat_from_yaw_pitch(std::atan2(-d.x, -d.z), 0.0);
    segments_.push_back(Segment{corners[i], corners[i + 1], path_length_m_, length_m, facing});
    path_length_m_ += length_m;
  }
}

Pose PolylineWalk::pose_at(des::Time t) const {
  return pose_at_distance(params_.speed_m_s * t.to_seconds());
}

Pose PolylineWalk::pose_at_distance(double s_m) const {
  if (segments_.empty()) return Pose{params_.points_m.front(), params_.orientation};
  double s = s_m;
  if (params_.loop) {
    s = std::fmod(s, path_length_m_);
    if (s < 0.0) s += path_length_m_;
  } else {
    s = std::clamp(s, 0.0, path_length_m_);
  }
  // The last segment starting at or before s; the first starts at 0 <= s.
  const auto it = std::upper_bound(segments_.begin(), segments_.end(), s,
                                   [](double v, const Segment& seg) { return v < seg.start_s_m; });
  const Segment& seg = *std::prev(it);
  const double f = std::clamp((s - seg.start_s_m) / seg.length_m, 0.0, 1.0);
  Pose p;
  // Interpolate from whichever end is nearer so endpoints come out exactly.
  p.position_m = f <= 0.5 ? seg.from_m + (seg.to_m - seg.from_m) * f
                          : seg.to_m + (seg.from_m - seg.to_m) * (1.0 - f);
  p.orientation = params_.face_direction ? seg.facing : params_.orientation;
  return p;
}

}  // namespace latsim::tracker
