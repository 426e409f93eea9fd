// Validity periods of priority rendering: how long an object's image in a
// display memory stays correct to within a threshold angle.
#pragma once

#include <glm/vec3.hpp>

#include "latsim/renderer/aabb.hpp"

namespace latsim::arp {

/// Distance the viewpoint may move sideways before a point at `distance_m`
/// appears displaced by `threshold_rad`: the chord 2 d sin(theta/2). The
/// textbook form d sqrt(2 (1 - cos theta)) is the same number on paper but
/// loses every digit to cancellation below about 1e-8 rad, so it is never used.
double translational_validity_distance_m(double distance_m, double threshold_rad);

/// Change of viewing distance that makes an object of radius `radius_m` seen
/// from `centre_distance_m` grow by `threshold_rad` in angular diameter
/// (approaching, the faster case). Written as r sin(delta) / (sin a sin(a + delta))
/// with a = atan(r / d) and delta = theta / 2, which is cot(a) - cot(a + delta)
/// without its cancellation. Infinite for a point (radius 0).
double size_validity_distance_m(double centre_distance_m, double radius_m, double threshold_rad);

/// Time a distance budget lasts at a speed: infinite when the speed is zero,
/// never NaN (a zero budget at zero speed is still infinite: nothing moves).
double period_from_distance_s(double distance_m, double speed_m_s);

/// What an object's validity depends on, seen from the current viewpoint.
struct ObjectView {
  double nearest_distance_m = 0.0;       ///< eye to the nearest point of the object
  double centre_distance_m = 0.0;        ///< eye to the object's centre
  double radius_m = 0.0;                 ///< bounding-sphere radius
  glm::dvec3 to_centre_unit{0.0, 0.0, -1.0};  ///< unit direction eye -> centre
  glm::dvec3 relative_velocity_m_s{0.0};      ///< object velocity minus eye velocity
  double animation_validity_s = 0.0;     ///< user-defined; <= 0 or infinity means static
};

/// The three components of an object's validity period and their minimum.
struct ValidityPeriods {
  double translational_s = 0.0;
  double size_s = 0.0;
  double animation_s = 0.0;
  double min_s() const;
};

/// Describes an object with bounds `bounds` seen from `eye_m`.
ObjectView view_of(const renderer::Aabb& bounds, const glm::dvec3& eye_m, const glm::dvec3& relative_velocity_m_s,
                   double animation_validity_s);

/// Validity periods of one object for a threshold angle.
ValidityPeriods validity_periods(const ObjectView& view, double threshold_rad);

}  // namespace latsim::arp
