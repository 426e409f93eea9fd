#include "latsim/tracker/imu.hpp"
#include "latsim/units/units.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace latsim::tracker {

namespace {

void check_finite_non_negative(double v, const char* what) {
  if (!std::isfinite(v) || v < 0.0)
    throw std::invalid_argument(std::string("IMU ") + what + " must be finite and not negative");
}

glm::dvec3 normal3(des::RandomStream& s, double stddev) {
  const double x = s.normal(0.0, stddev), y = s.normal(0.0, stddev), z = s.normal(0.0, stddev);
  return {x, y, z};
}

}  // namespace

Imu::Imu(ImuParams params, des::PeriodicSchedule schedule, const MotionSource& motion, des::RandomStream stream)
    : params_(params),
      schedule_(schedule),
      motion_(motion),
      noise_stream_(stream.substream("noise")),
      bias_stream_(stream.substream("bias")) {
  check_finite_non_negative(params_.gyro_noise_density_deg_s_rthz, "noise density");
  check_finite_non_negative(params_.gyro_bias_deg_s, "bias");
  check_finite_non_negative(params_.bias_instability_deg_s, "bias instability");
  if (!(params_.range_deg_s > 0.0)) throw std::invalid_argument("IMU range must be positive");
  if (params_.timestamp_tick < des::Time::zero()) throw std::invalid_argument("IMU timestamp tick is negative");
  if (params_.bias_instability_deg_s > 0.0 && params_.bias_correlation <= des::Time::zero())
    throw std::invalid_argument("IMU bias correlation time must be positive");
  // Nothing is drawn unless the scenario asks for it: a noise-free IMU
  // leaves both streams untouched.
  if (params_.gyro_bias_deg_s > 0.0) turn_on_bias_rad_s_ = normal3(bias_stream_, params_.gyro_bias_deg_s * units::kRadPerDeg);
  if (params_.bias_instability_deg_s > 0.0)
    wander_rad_s_ = normal3(bias_stream_, params_.bias_instability_deg_s * units::kRadPerDeg);
}

glm::dvec3 Imu::bias_at(int64_t k) {
  if (params_.bias_instability_deg_s > 0.0 && any_) {
    // First-order Gauss-Markov over the steps since the last reading:
    // b <- b a^n + sigma sqrt(1 - a^2n) N(0, 1), exact for any gap.
    const double dt = (schedule_.at(k) - schedule_.at(last_index_)).to_seconds();
    const double a = std::exp(-dt / params_.bias_correlation.to_seconds());
    const double sigma = params_.bias_instability_deg_s * units::kRadPerDeg * std::sqrt(std::max(0.0, 1.0 - a * a));
    wander_rad_s_ = wander_rad_s_ * a + normal3(bias_stream_, sigma);
  }
  return turn_on_bias_rad_s_ + wander_rad_s_;
}

ImuReading Imu::read(int64_t k) {
  if (any_ && k <= last_index_)
    throw std::logic_error("IMU readings must be asked for in increasing index (asked for " + std::to_string(k) +
                           " after " + std::to_string(last_index_) + ")");
  const des::Time t = schedule_.at(k), before = schedule_.at(k - 1);
  const glm::dquat q0 = motion_.pose_at(before).orientation, q1 = motion_.pose_at(t).orientation;
  // The body-frame increment q0^-1 q1 over the interval: integrating the
  // noise-free readings reproduces the true orientation at every sample.
  glm::dvec3 rate = rotation_vector_of(glm::inverse(q0) * q1) / (t - before).to_seconds();
  rate += bias_at(k);
  if (params_.gyro_noise_density_deg_s_rthz > 0.0) {
    const double per_reading = params_.gyro_noise_density_deg_s_rthz * units::kRadPerDeg / std::sqrt((t - before).to_seconds());
    rate += normal3(noise_stream_, per_reading);
  }
  const double range = params_.range_deg_s * units::kRadPerDeg;
  rate = glm::clamp(rate, glm::dvec3(-range), glm::dvec3(range));
  ImuReading r;
  r.index = k;
  r.measured_at = t;
  const int64_t tick = params_.timestamp_tick.ticks();
  r.stamp = tick > 0 ? des::Time::ps(t.ticks() - ((t.ticks() % tick) + tick) % tick) : t;
  r.rate_rad_s = rate;
  last_index_ = k;
  any_ = true;
  return r;
}

}  // namespace latsim::tracker
