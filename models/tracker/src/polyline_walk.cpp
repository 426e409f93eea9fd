#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "latsim/tracker/motion_source.hpp"
#include "latsim/units/units.hpp"

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
  if (!(params_.turn_rate_deg_s >= 0.0) || !std::isfinite(params_.turn_rate_deg_s))
    throw std::invalid_argument("turn rate must be finite and not negative");
  if (!params_.face_direction || params_.turn_rate_deg_s == 0.0) return;
  // Each corner's turn takes angle / rate, centred on the corner: it starts
  // half of that walk before it and ends half after, at most half of either leg.
  const size_t n = segments_.size();
  for (size_t i = 0; i < n; ++i) {
    if (i == 0 && !params_.loop) continue;
    const Segment& before = segments_[(i + n - 1) % n];
    Segment& after = segments_[i];
    const double cos_half = std::min(1.0, std::abs(glm::dot(before.facing, after.facing)));
    const double angle_deg = units::rad_to_deg(2.0 * std::acos(cos_half));
    const double walk_m = params_.speed_m_s * angle_deg / params_.turn_rate_deg_s;
    after.turn_in_m = std::min({walk_m / 2.0, before.length_m / 2.0, after.length_m / 2.0});
  }
}

glm::dquat PolylineWalk::facing_at(size_t i, double s) const {
  const size_t n = segments_.size();
  const Segment& seg = segments_[i];
  // The turn into this segment, and the turn into the next (or, looping, the first).
  if (seg.turn_in_m > 0.0 && s - seg.start_s_m < seg.turn_in_m) {
    const Segment& before = segments_[(i + n - 1) % n];
    const double f = 0.5 + (s - seg.start_s_m) / (2.0 * seg.turn_in_m);
    return glm::slerp(before.facing, seg.facing, f);
  }
  const bool has_next = i + 1 < n || params_.loop;
  if (has_next) {
    const Segment& next = segments_[(i + 1) % n];
    const double to_end = seg.start_s_m + seg.length_m - s;
    if (next.turn_in_m > 0.0 && to_end < next.turn_in_m) {
      const double f = 0.5 - to_end / (2.0 * next.turn_in_m);
      return glm::slerp(seg.facing, next.facing, f);
    }
  }
  return seg.facing;
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
  p.orientation = params_.face_direction ? facing_at(static_cast<size_t>(std::prev(it) - segments_.begin()), s)
                                         : params_.orientation;
  return p;
}

}  // namespace latsim::tracker
