#include "latsim/des/clock.hpp"

#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace latsim::des {

namespace {
constexpr int64_t kPartsPerBillion = 1'000'000'000;
}  // namespace

RationalSeconds period_with_rate_error(RationalSeconds nominal, double rate_error_ppm) {
  if (!std::isfinite(rate_error_ppm) || std::abs(rate_error_ppm) > 1e5)
    throw std::invalid_argument("clock rate error must lie within ±1e5 ppm");
  if (nominal.num <= 0 || nominal.den <= 0) throw std::invalid_argument("clock period must be positive");
  const int64_t ppb = std::llround(rate_error_ppm * 1e3);
  if (ppb == 0) return nominal;
  // A faster clock (ppb > 0) has a shorter period: T = T0 / (1 + ppb / 1e9).
  __int128 num = static_cast<__int128>(nominal.num) * kPartsPerBillion;
  __int128 den = static_cast<__int128>(nominal.den) * (kPartsPerBillion + ppb);
  __int128 a = num, b = den;
  while (b != 0) {
    const __int128 r = a % b;
    a = b;
    b = r;
  }
  num /= a;
  den /= a;
  constexpr __int128 kMax = std::numeric_limits<int64_t>::max();
  if (num > kMax || den > kMax) throw std::invalid_argument("clock period with its rate error is not representable");
  return RationalSeconds{static_cast<int64_t>(num), static_cast<int64_t>(den)};
}

Clock resolve_clock(std::string name, RationalSeconds nominal, const ClockSettings& settings, RandomStream& stream) {
  Clock c;
  c.name = std::move(name);
  c.nominal = nominal;
  c.period = period_with_rate_error(nominal, settings.rate_error_ppm);
  c.rate_error_ppm = settings.rate_error_ppm;
  if (settings.phase) {
    c.phase = *settings.phase;
    return c;
  }
  // One whole period in ticks (the schedule's first interval), every tick equally likely.
  const int64_t ticks = PeriodicSchedule(Time::zero(), c.period).nominal_period().ticks();
  c.phase = Time::ps(static_cast<int64_t>(stream.uniform_int(static_cast<uint64_t>(std::max<int64_t>(ticks, 1)))));
  c.drawn = true;
  return c;
}

}  // namespace latsim::des
