#include "latsim/display/clock_noise.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace latsim::display {

namespace {

constexpr double kPsPerSecond = 1e12;

// A random walk reflected into [-bound, bound].
double reflect(double v, double bound) {
  if (bound <= 0.0) return 0.0;
  const double span = 4.0 * bound;
  double u = std::fmod(v + bound, span);  // position on a circle of twice the interval
  if (u < 0.0) u += span;
  return (u <= 2.0 * bound ? u : span - u) - bound;
}

}  // namespace

ClockNoise::ClockNoise(ClockNoiseParams params, des::RationalSeconds period, des::Time slack, int64_t fields,
                       des::RandomStream stream)
    : params_(params), period_s_(period.to_seconds()) {
  if (params_.jitter_rms < des::Time::zero()) throw std::invalid_argument("clock jitter must not be negative");
  if (!(params_.wander_ppm_per_sqrt_s >= 0.0) || !std::isfinite(params_.wander_ppm_per_sqrt_s))
    throw std::invalid_argument("clock wander must be finite and not negative");
  if (slack < des::Time::ps(8))
    throw std::invalid_argument("the display has no blank time after a field's last pixel for its clock to move in");
  const double slack_ps = static_cast<double>(slack.ticks());
  max_rate_ppm_ = slack_ps / 4.0 / (period_s_ * kPsPerSecond) * 1e6;
  jitter_bound_ = std::min(params_.jitter_rms * 4, des::Time::ps(slack.ticks() / 4));
  const double sigma_ps = static_cast<double>(params_.jitter_rms.ticks());
  const double bound_ps = static_cast<double>(jitter_bound_.ticks());
  const double step_ppm = params_.wander_ppm_per_sqrt_s * std::sqrt(period_s_);
  const double ps_per_ppm = period_s_ * kPsPerSecond * 1e-6;

  offsets_.assign(static_cast<size_t>(std::max<int64_t>(fields, 1)), 0);
  double wander_ps = 0.0, rate_ppm = 0.0;
  for (size_t k = 1; k < offsets_.size(); ++k) {
    wander_ps += rate_ppm * ps_per_ppm;
    if (step_ppm > 0.0) rate_ppm = reflect(rate_ppm + step_ppm * stream.normal(), max_rate_ppm_);
    double jitter_ps = 0.0;
    if (sigma_ps > 0.0) jitter_ps = std::clamp(sigma_ps * stream.normal(), -bound_ps, bound_ps);
    offsets_[k] = std::llround(wander_ps + jitter_ps);
  }
  last_wander_ps_ = wander_ps;
  last_rate_ppm_ = rate_ppm;
}

des::Time ClockNoise::offset(int64_t field) const {
  if (field <= 0) return des::Time::zero();
  const auto n = static_cast<int64_t>(offsets_.size());
  if (field < n) return des::Time::ps(offsets_[static_cast<size_t>(field)]);
  const double ps_per_ppm = period_s_ * kPsPerSecond * 1e-6;
  return des::Time::ps(std::llround(last_wander_ps_ + static_cast<double>(field - (n - 1)) * last_rate_ppm_ * ps_per_ppm));
}

}  // namespace latsim::display
