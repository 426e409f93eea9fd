// Simulation time: a strong integer type counting picoseconds.
//
// Range: int64 picoseconds cover +-9.22e6 s (about 106 days) of simulated
// time; arithmetic that would leave that range throws TimeOverflow instead of
// wrapping. Build values only through the factories (Time::ms(16)), never
// from raw integers of unknown unit.
#pragma once

#include <compare>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace latsim::des {

/// Thrown when time arithmetic or conversion would leave the int64 range.
class TimeOverflow : public std::overflow_error {
 public:
  using std::overflow_error::overflow_error;
};

/// A point or span of simulated time, an int64 count of picoseconds.
class Time {
 public:
  static constexpr int64_t kTicksPerSecond = 1'000'000'000'000;

  constexpr Time() = default;

  static constexpr Time ps(int64_t v) { return Time(v); }
  static constexpr Time ns(int64_t v) { return Time(scaled(v, 1'000)); }
  static constexpr Time us(int64_t v) { return Time(scaled(v, 1'000'000)); }
  static constexpr Time ms(int64_t v) { return Time(scaled(v, 1'000'000'000)); }
  static constexpr Time s(int64_t v) { return Time(scaled(v, kTicksPerSecond)); }
  /// Nearest tick to a duration in seconds; throws on NaN or out of range.
  static Time from_seconds(double seconds) { return from_scaled(seconds, 1e12, "s"); }
  // Scaled straight to ticks: going through seconds would round twice.
  static Time from_ms(double milliseconds) { return from_scaled(milliseconds, 1e9, "ms"); }
  static Time from_us(double microseconds) { return from_scaled(microseconds, 1e6, "us"); }
  static constexpr Time zero() { return Time(0); }
  static constexpr Time max() { return Time(std::numeric_limits<int64_t>::max()); }

  constexpr int64_t ticks() const { return ticks_; }
  constexpr double to_seconds() const { return static_cast<double>(ticks_) * 1e-12; }
  constexpr double to_ms() const { return static_cast<double>(ticks_) * 1e-9; }
  /// Human-readable, e.g. "16.683333 ms".
  std::string str() const;

  constexpr auto operator<=>(const Time&) const = default;

  constexpr Time operator+(Time o) const { return Time(checked_add(ticks_, o.ticks_)); }
  constexpr Time operator-(Time o) const { return Time(checked_sub(ticks_, o.ticks_)); }
  constexpr Time operator-() const { return Time(checked_sub(0, ticks_)); }
  constexpr Time operator*(int64_t k) const { return Time(checked_mul(ticks_, k)); }
  constexpr Time& operator+=(Time o) { return *this = *this + o; }
  constexpr Time& operator-=(Time o) { return *this = *this - o; }
  /// Integer quotient of two spans (how many whole `o` fit in this).
  constexpr int64_t operator/(Time o) const {
    check_divisor(o);
    return ticks_ / o.ticks_;
  }
  constexpr Time operator%(Time o) const {
    check_divisor(o);
    return Time(ticks_ % o.ticks_);
  }

 private:
  constexpr explicit Time(int64_t t) : ticks_(t) {}

  static Time from_scaled(double value, double ticks_per_unit, const char* unit);

  // Division by a zero span, or of the most negative time by -1 ps, has no
  // int64 result; both are reported instead of crashing.
  constexpr void check_divisor(Time o) const {
    if (o.ticks_ == 0) throw std::domain_error("division of simulation time by a zero span");
    if (o.ticks_ == -1 && ticks_ == std::numeric_limits<int64_t>::min())
      throw TimeOverflow("simulation time overflow in division");
  }

  static constexpr int64_t checked_add(int64_t a, int64_t b) {
    int64_t r = 0;
    if (__builtin_add_overflow(a, b, &r)) throw TimeOverflow("simulation time overflow in addition");
    return r;
  }
  static constexpr int64_t checked_sub(int64_t a, int64_t b) {
    int64_t r = 0;
    if (__builtin_sub_overflow(a, b, &r)) throw TimeOverflow("simulation time overflow in subtraction");
    return r;
  }
  static constexpr int64_t checked_mul(int64_t a, int64_t b) {
    int64_t r = 0;
    if (__builtin_mul_overflow(a, b, &r)) throw TimeOverflow("simulation time overflow in multiplication");
    return r;
  }
  static constexpr int64_t scaled(int64_t v, int64_t unit) { return checked_mul(v, unit); }

  int64_t ticks_ = 0;
};

constexpr Time operator*(int64_t k, Time t) { return t * k; }

/// An exact positive rational number of seconds, e.g. {1001, 60000}.
struct RationalSeconds {
  int64_t num = 0;
  int64_t den = 1;
  /// The period of a frequency given as an exact rational in hertz.
  static RationalSeconds period_of_hz(int64_t hz_num, int64_t hz_den = 1);
  double to_seconds() const { return static_cast<double>(num) / static_cast<double>(den); }
};

/// Times of a periodic event: t_k = t0 + floor(k * num * 1e12 / den) ticks,
/// computed from the index k in 128-bit arithmetic, never accumulated, so the
/// billionth period is exactly where it should be.
class PeriodicSchedule {
 public:
  PeriodicSchedule() = default;
  PeriodicSchedule(Time t0, RationalSeconds period);

  /// Time of occurrence k (k may be negative for times before t0).
  Time at(int64_t k) const;
  /// Smallest k with at(k) >= t.
  int64_t index_at_or_after(Time t) const;
  /// Largest k with at(k) <= t.
  int64_t index_at_or_before(Time t) const;
  Time origin() const { return t0_; }
  RationalSeconds period() const { return period_; }
  /// The period rounded down to a tick (for reporting; never accumulate it).
  Time nominal_period() const { return at(1) - at(0); }

 private:
  Time t0_;
  RationalSeconds period_{1, 1};
};

}  // namespace latsim::des
