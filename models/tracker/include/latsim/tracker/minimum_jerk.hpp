// Sudden, deliberate movements: minimum-jerk turns separated by rests.
#pragma once

#include <glm/vec3.hpp>

#include "latsim/des/time.hpp"
#include "latsim/tracker/motion_source.hpp"

namespace latsim::tracker {

/// Settings of MinimumJerkMotion.
struct MinimumJerkParams {
  double amplitude_deg = 30.0;                ///< angle of one movement
  des::Time duration = des::Time::ms(500);    ///< length of one movement
  des::Time rest = des::Time::ms(500);        ///< stillness before each movement
  des::Time delay;                            ///< the pattern starts this late (still until then)
  glm::dvec3 axis{0.0, 1.0, 0.0};             ///< world rotation axis (normalised by the source)
  /// Alternate: back and forth between the start and the amplitude; otherwise
  /// every movement turns further the same way.
  bool alternate = true;
  Pose start;                                 ///< pose before the first movement
};

/// Repeated minimum-jerk turns (Flash and Hogan, 1985): after a rest, the
/// angle about `axis` moves by A·(10τ³ − 15τ⁴ + 6τ⁵), τ = (t − t_k)/D in
/// [0, 1], whose velocity and acceleration are zero at both ends and whose
/// peak speed, at τ = 1/2, is 1.875·A/D. Movement k starts at
/// t_k = delay + rest + k·(rest + duration); times come from integer
/// division of t by that period, so the pattern does not drift over long runs.
class MinimumJerkMotion final : public MotionSource {
 public:
  /// Throws std::invalid_argument for a zero axis, a non-positive duration,
  /// a negative rest or a non-finite amplitude.
  explicit MinimumJerkMotion(MinimumJerkParams params);
  Pose pose_at(des::Time t) const override;
  std::string name() const override { return "minimum_jerk"; }
  bool is_still() const override { return params_.amplitude_deg == 0.0; }
  /// The angle about the axis at t, in degrees from the start orientation.
  double angle_deg_at(des::Time t) const;
  /// The normalised profile s(τ) = 10τ³ − 15τ⁴ + 6τ⁵ (clamped outside [0, 1]).
  static double profile(double tau);
  /// Start of movement k.
  des::Time movement_start(int64_t k) const {
    return params_.delay + params_.rest + (params_.rest + params_.duration) * k;
  }

 private:
  MinimumJerkParams params_;
  glm::dvec3 axis_;
};

}  // namespace latsim::tracker
