#include "latsim/arp/validity.hpp"
#include "latsim/units/units.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace latsim::arp {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

void check_threshold(double threshold_rad) {
  if (!(threshold_rad > 0.0) || !(threshold_rad < units::kPi)) {
    throw std::invalid_argument("validity: threshold angle must lie in (0, pi) rad");
  }
}

}  // namespace

double translational_validity_distance_m(double distance_m, double threshold_rad) {
  check_threshold(threshold_rad);
  if (!(distance_m >= 0.0)) throw std::invalid_argument("validity: distance must be >= 0");
  return 2.0 * distance_m * std::sin(0.5 * threshold_rad);
}

double size_validity_distance_m(double centre_distance_m, double radius_m, double threshold_rad) {
  check_threshold(threshold_rad);
  if (!(centre_distance_m >= 0.0) || !(radius_m >= 0.0)) {
    throw std::invalid_argument("validity: distances must be >= 0");
  }
  if (radius_m == 0.0) return kInfinity;
  const double half_angle = std::atan2(radius_m, centre_distance_m);
  const double delta = 0.5 * threshold_rad;
  return radius_m * std::sin(delta) / (std::sin(half_angle) * std::sin(half_angle + delta));
}

double period_from_distance_s(double distance_m, double speed_m_s) {
  if (!(speed_m_s > 0.0)) return kInfinity;
  return distance_m / speed_m_s;
}

double ValidityPeriods::min_s() const { return std::min({translational_s, size_s, animation_s}); }

ObjectView view_of(const renderer::Aabb& bounds, const glm::dvec3& eye_m, const glm::dvec3& relative_velocity_m_s,
                   double animation_validity_s) {
  ObjectView view;
  const glm::dvec3 nearest = glm::clamp(eye_m, bounds.min_m, bounds.max_m);
  view.nearest_distance_m = glm::length(nearest - eye_m);
  const glm::dvec3 to_centre = bounds.centre_m() - eye_m;
  view.centre_distance_m = glm::length(to_centre);
  view.radius_m = 0.5 * glm::length(bounds.size_m());
  // An eye at the centre has no direction to it; any unit vector serves, the
  // radial speed then only feeds the size term of an object the eye is inside.
  view.to_centre_unit = view.centre_distance_m > 0.0 ? to_centre / view.centre_distance_m : glm::dvec3(0.0, 0.0, -1.0);
  view.relative_velocity_m_s = relative_velocity_m_s;
  view.animation_validity_s = animation_validity_s;
  return view;
}

ValidityPeriods validity_periods(const ObjectView& view, double threshold_rad) {
  ValidityPeriods p;
  const double speed = glm::length(view.relative_velocity_m_s);
  p.translational_s = period_from_distance_s(translational_validity_distance_m(view.nearest_distance_m, threshold_rad), speed);
  // Only motion along the line of sight changes apparent size.
  const double radial_speed = std::abs(glm::dot(view.relative_velocity_m_s, view.to_centre_unit));
  p.size_s = period_from_distance_s(size_validity_distance_m(view.centre_distance_m, view.radius_m, threshold_rad), radial_speed);
  p.animation_s = view.animation_validity_s > 0.0 ? view.animation_validity_s : kInfinity;
  return p;
}

}  // namespace latsim::arp
