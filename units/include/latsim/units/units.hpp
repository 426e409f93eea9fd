// Units and angle constants, defined once for every library: a scenario
// speaks in degrees, the models' trigonometry in radians, the figures in
// degrees and arc minutes.
#pragma once

#include <numbers>

namespace latsim::units {

inline constexpr double kPi = std::numbers::pi;
/// Radians per degree, pi / 180.
inline constexpr double kRadPerDeg = kPi / 180.0;
/// Degrees per radian, 180 / pi.
inline constexpr double kDegPerRad = 180.0 / kPi;
inline constexpr double kArcminPerDeg = 60.0;
/// Arc minutes per radian, 10800 / pi.
inline constexpr double kArcminPerRad = 10800.0 / kPi;

/// An angle in degrees, in radians: deg x pi / 180, multiplied first. (A
/// product with kRadPerDeg, rounded once more, may differ in the last bit:
/// each place keeps the form its pinned results were computed with.)
constexpr double deg_to_rad(double deg) { return deg * kPi / 180.0; }
/// An angle in radians, in degrees: rad x 180 / pi, multiplied first.
constexpr double rad_to_deg(double rad) { return rad * 180.0 / kPi; }

}  // namespace latsim::units
