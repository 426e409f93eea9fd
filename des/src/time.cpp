#include "latsim/des/time.hpp"

#include <cmath>
#include <cstdio>
#include <numeric>

namespace latsim::des {

Time Time::from_scaled(double value, double ticks_per_unit, const char* unit) {
  if (!std::isfinite(value))
    throw TimeOverflow(std::string("simulation time from a non-finite number of ") + unit);
  const double ticks = std::nearbyint(value * ticks_per_unit);
  // 2^63 is exactly representable; anything at or beyond it does not fit.
  if (ticks >= 9223372036854775808.0 || ticks < -9223372036854775808.0) {
    // At most 17 significant digits, with an exponent when large: never a 170-digit number.
    char shown[32];
    std::snprintf(shown, sizeof shown, "%.17g", value);
    throw TimeOverflow(std::string("simulation time out of range: ") + shown + " " + unit +
                       " (the int64 picosecond range is about +-106 days)");
  }
  return Time::ps(static_cast<int64_t>(ticks));
}

std::string Time::str() const {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.6f ms", to_ms());
  return buf;
}

RationalSeconds RationalSeconds::period_of_hz(int64_t hz_num, int64_t hz_den) {
  if (hz_num <= 0 || hz_den <= 0) throw std::invalid_argument("frequency must be positive");
  const int64_t g = std::gcd(hz_num, hz_den);
  return RationalSeconds{hz_den / g, hz_num / g};
}

namespace {

using i128 = __int128;

// floor(a / b) for b > 0.
i128 floor_div(i128 a, i128 b) {
  i128 q = a / b;
  if ((a % b != 0) && (a < 0)) --q;
  return q;
}

int64_t to_i64(i128 v) {
  if (v > static_cast<i128>(INT64_MAX) || v < static_cast<i128>(INT64_MIN))
    throw TimeOverflow("periodic schedule index out of the time range");
  return static_cast<int64_t>(v);
}

}  // namespace

PeriodicSchedule::PeriodicSchedule(Time t0, RationalSeconds period) : t0_(t0), period_(period) {
  if (period.num <= 0 || period.den <= 0) throw std::invalid_argument("period must be a positive rational");
}

Time PeriodicSchedule::at(int64_t k) const {
  // |k * num * 1e12| < 2^63 * 2^63 * 2^40 could exceed 128 bits: check it.
  i128 scaled = 0;
  if (__builtin_mul_overflow(static_cast<i128>(k), static_cast<i128>(period_.num) * Time::kTicksPerSecond, &scaled))
    throw TimeOverflow("periodic schedule index out of the time range");
  // Add t0 before narrowing: an offset beyond int64 may still land in range
  // when t0 is negative.
  return Time::ps(to_i64(static_cast<i128>(t0_.ticks()) + floor_div(scaled, period_.den)));
}

int64_t PeriodicSchedule::index_at_or_after(Time t) const {
  // at(k) >= t  <=>  floor(k*P/den) >= d  <=>  k*P >= d*den  (d integer), P = num*1e12.
  const i128 d = static_cast<i128>(t.ticks()) - t0_.ticks();
  const i128 p = static_cast<i128>(period_.num) * Time::kTicksPerSecond;
  const i128 k = -floor_div(-(d * period_.den), p);  // ceil(d*den / p)
  return to_i64(k);
}

int64_t PeriodicSchedule::index_at_or_before(Time t) const {
  // at(k) <= t  <=>  floor(k*P/den) <= d  <=>  k*P < (d+1)*den.
  const i128 d = static_cast<i128>(t.ticks()) - t0_.ticks();
  const i128 p = static_cast<i128>(period_.num) * Time::kTicksPerSecond;
  const i128 k = floor_div((d + 1) * period_.den - 1, p);
  return to_i64(k);
}

}  // namespace latsim::des
