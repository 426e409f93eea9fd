// An inertial measurement unit's gyroscope as a headset's tracker reads it:
// periodic readings of the angular rate with white noise, a bias that
// wanders, quantised device timestamps and a measuring range.
#pragma once

#include <cstdint>
#include <deque>

#include <glm/vec3.hpp>

#include "latsim/des/clock.hpp"
#include "latsim/des/random.hpp"
#include "latsim/des/time.hpp"
#include "latsim/tracker/motion_source.hpp"

namespace latsim::tracker {

/// A gyroscope as its datasheet (or a recording of it) describes it.
struct ImuParams {
  /// White rate noise (angle random walk), deg/s per sqrt(Hz): a reading at
  /// rate f has a per-axis standard deviation of noise_density * sqrt(f).
  double gyro_noise_density_deg_s_rthz = 0.0;
  /// Residual bias after the factory calibration, deg/s per axis: drawn once
  /// per replication (normal, this standard deviation).
  double gyro_bias_deg_s = 0.0;
  /// Bias instability: a first-order Gauss-Markov wander of this standard
  /// deviation (deg/s per axis) and correlation time (0: none).
  double bias_instability_deg_s = 0.0;
  des::Time bias_correlation = des::Time::s(100);
  /// The device clock's tick: timestamps are whole ticks (0: exact).
  des::Time timestamp_tick;
  /// Readings saturate at +-range (deg/s per axis).
  double range_deg_s = 2000.0;
};

/// One gyroscope reading: the mean body-frame angular rate over the interval
/// ending at its sampling instant, as the device reports it.
struct ImuReading {
  int64_t index = 0;
  des::Time measured_at;         ///< the true sampling instant
  des::Time stamp;               ///< the device's timestamp of it (quantised)
  glm::dvec3 rate_rad_s{0.0};    ///< body frame, noise, bias and saturation included
};

/// Samples a motion's angular rate at phase + k * period. Reading k is the
/// rotation from sample k-1 to sample k expressed in the body frame, over the
/// interval (exact for integration: the true orientation is the product of
/// the noise-free readings' increments), plus bias and white noise, clipped
/// to the range. Noise and bias draw from substreams "noise" and "bias" of
/// the given stream; readings must be asked for in increasing index.
class Imu {
 public:
  Imu(ImuParams params, des::PeriodicSchedule schedule, const MotionSource& motion, des::RandomStream stream);

  /// Reading k; throws std::logic_error for an index not above the last one.
  ImuReading read(int64_t k);
  des::Time time_of(int64_t k) const { return schedule_.at(k); }
  int64_t first_index_at_or_after(des::Time t) const { return schedule_.index_at_or_after(t); }
  const ImuParams& params() const { return params_; }

 private:
  glm::dvec3 bias_at(int64_t k);

  ImuParams params_;
  des::PeriodicSchedule schedule_;
  const MotionSource& motion_;
  des::RandomStream noise_stream_;
  des::RandomStream bias_stream_;
  glm::dvec3 turn_on_bias_rad_s_{0.0};
  glm::dvec3 wander_rad_s_{0.0};
  int64_t last_index_ = -1;
  bool any_ = false;
};

}  // namespace latsim::tracker
