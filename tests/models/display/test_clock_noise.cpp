// Display clock jitter and wander: measured statistics of retrace times
// against the configured ones, with tolerances from the sample sizes.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "latsim/des/random.hpp"
#include "latsim/display/clock_noise.hpp"
#include "latsim/display/raster_timing.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using latsim::des::RandomStream;
using latsim::des::RationalSeconds;
using latsim::des::Time;
using latsim::display::ClockNoise;
using latsim::display::ClockNoiseParams;
using latsim::display::RasterParams;
using latsim::display::RasterTiming;

namespace {

// 640 x 480 progressive at 60 Hz, 22 blank lines, 160 blank pixels a line.
RasterParams raster_60() { return RasterParams{}; }

RasterTiming noisy(ClockNoiseParams params, int64_t fields, uint64_t seed) {
  RasterTiming t(raster_60(), Time::us(250));
  t.set_clock_noise(std::make_shared<const ClockNoise>(params, t.params().field_period, t.end_slack(), fields,
                                                       RandomStream(seed, "test.clock_noise")));
  return t;
}

// Variance of a standard normal cut (clamped) at ±a: the mass beyond ±a sits
// at ±a, so E[X²] = (1 - 2Q(a) - 2aφ(a)) + 2Q(a)a², Q the upper tail.
double clamped_normal_variance(double a) {
  const double phi = std::exp(-a * a / 2.0) / std::sqrt(2.0 * units::kPi);
  const double q = 0.5 * std::erfc(a / std::sqrt(2.0));
  return 1.0 - 2.0 * q - 2.0 * a * phi + 2.0 * q * a * a;
}

}  // namespace

TEST_CASE("Display clock: the blank time after a field's last pixel is the slack the clock may use") {
  const RasterTiming t(raster_60());
  // The last pixel is slot (22 + 479) x 800 + 639 of 502 x 800 slots; the
  // 161 slots after it are 161 / (502 x 800 x 60) s = 6.682 us.
  const double expected_ps = 161.0 / (502.0 * 800.0 * 60.0) * 1e12;
  CHECK(std::abs(static_cast<double>(t.end_slack().ticks()) - expected_ps) <= 2.0);
}

TEST_CASE("Display clock jitter: retraces scatter by the configured rms, intervals by sqrt(2) of it") {
  const double sigma_ps = 100e3;  // 100 ns
  const int64_t n = 100001;
  ClockNoiseParams p;
  p.jitter_rms = Time::ps(static_cast<int64_t>(sigma_ps));
  const RasterTiming t = noisy(p, n, 7);
  const RasterTiming steady(raster_60(), Time::us(250));

  // J(k) = field_start(k) - steady start, k >= 1, are independent; the cut at
  // 4 sigma (below a quarter of the 6.68 us slack) keeps this much variance.
  const double cut = clamped_normal_variance(4.0);
  double sum_j2 = 0.0, sum_d2 = 0.0;
  int64_t n_j = 0, n_d = 0;
  double max_abs_j = 0.0;
  for (int64_t k = 1; k < n; ++k) {
    const double j = static_cast<double>((t.field_start(k) - steady.field_start(k)).ticks());
    sum_j2 += j * j;
    max_abs_j = std::max(max_abs_j, std::abs(j));
    ++n_j;
  }
  // Interval errors J(k+1) - J(k) over disjoint pairs (k odd) are
  // independent, each with variance 2 sigma² (times the cut's factor).
  for (int64_t k = 1; k + 1 < n; k += 2) {
    const double d = static_cast<double>(((t.field_start(k + 1) - t.field_start(k)) -
                                          (steady.field_start(k + 1) - steady.field_start(k)))
                                             .ticks());
    sum_d2 += d * d;
    ++n_d;
  }
  const double var_j = sum_j2 / static_cast<double>(n_j);
  const double var_d = sum_d2 / static_cast<double>(n_d);
  // A variance estimated from m normal samples has relative standard error
  // sqrt(2/m): allow five of them.
  const double tol_j = 5.0 * std::sqrt(2.0 / static_cast<double>(n_j));
  const double tol_d = 5.0 * std::sqrt(2.0 / static_cast<double>(n_d));
  CHECK(var_j / (sigma_ps * sigma_ps * cut) == Approx(1.0).margin(tol_j));
  CHECK(var_d / (2.0 * sigma_ps * sigma_ps * cut) == Approx(1.0).margin(tol_d));
  // Bounded: never beyond the cut (plus the rounding to a tick).
  CHECK(max_abs_j <= 4.0 * sigma_ps + 1.0);
  CHECK(max_abs_j > 3.0 * sigma_ps);  // 1e5 draws reach 3 sigma (p of none ~ e^-270)
}

TEST_CASE("Display clock wander: the rate's variance grows linearly with time") {
  // Rate r(k) of field k from its interval: (interval - steady interval) / (T x 1e-6).
  const double w = 1.0;  // ppm per sqrt(s)
  const double period_s = 1.0 / 60.0;
  const double ps_per_ppm = period_s * 1e12 * 1e-6;
  const int m = 2000;  // independent runs
  const int64_t at[] = {1500, 3000, 6000};
  double sum_r2[3] = {0.0, 0.0, 0.0};
  ClockNoiseParams p;
  p.wander_ppm_per_sqrt_s = w;
  const RasterTiming steady(raster_60(), Time::us(250));
  for (int run = 0; run < m; ++run) {
    const RasterTiming t = noisy(p, 6002, static_cast<uint64_t>(run) + 1);
    for (int i = 0; i < 3; ++i) {
      const int64_t k = at[i];
      const double interval_error_ps =
          static_cast<double>(((t.field_start(k + 1) - t.field_start(k)) - (steady.field_start(k + 1) - steady.field_start(k)))
                                  .ticks());
      const double r = interval_error_ps / ps_per_ppm;
      sum_r2[i] += r * r;
    }
  }
  // r(k) is a sum of k independent steps of variance w² T: Var r(k) = w² k T
  // (25, 50 and 100 ppm² here; the reflection at the slack's 100 ppm is 10
  // standard deviations away at 100 s and does not show). Tolerance: five
  // relative standard errors of a variance from m samples.
  const double tol = 5.0 * std::sqrt(2.0 / m);
  for (int i = 0; i < 3; ++i) {
    const double expected = w * w * static_cast<double>(at[i]) * period_s;
    INFO("field " << at[i] << ": measured " << sum_r2[i] / m << " ppm², expected " << expected);
    CHECK(sum_r2[i] / m / expected == Approx(1.0).margin(tol));
  }
}

TEST_CASE("Display clock noise keeps retraces in order and field lookups consistent with field_start") {
  ClockNoiseParams p;
  p.jitter_rms = Time::ps(400000);  // 400 ns: 4 sigma = a quarter of the slack, the largest allowed
  p.wander_ppm_per_sqrt_s = 200.0;  // reaches the reflecting bound within seconds
  const int64_t n = 20000;
  const RasterTiming t = noisy(p, n, 3);
  const int last_line = t.lines_per_field() - 1, last_x = t.params().width_px - 1;
  RandomStream probe(11, "test.probe");
  for (int64_t k = -3; k < n + 40; ++k) {
    // A field starts after the previous one's last pixel was lit.
    REQUIRE(t.field_start(k + 1) > t.pixel_time(k, last_line, last_x));
    // Retrace instants, the tick before and a random instant between retraces.
    const Time s = t.field_start(k);
    REQUIRE(t.field_at_or_after(s) == k);
    REQUIRE(t.field_at_or_before(s) == k);
    REQUIRE(t.field_at_or_after(s - Time::ps(1)) == k);
    REQUIRE(t.field_at_or_before(s - Time::ps(1)) == k - 1);
    const Time mid = s + Time::ps(static_cast<int64_t>(
                             probe.uniform01() * static_cast<double>((t.field_start(k + 1) - s).ticks() - 1)) + 1);
    REQUIRE(t.field_at_or_after(mid) == k + 1);
    REQUIRE(t.field_at_or_before(mid) == k);
  }
}

TEST_CASE("Display clock noise is drawn from its stream: same seed, same retraces, and a steady clock has none") {
  ClockNoiseParams p;
  p.jitter_rms = Time::ps(50000);
  p.wander_ppm_per_sqrt_s = 0.5;
  const RasterTiming a = noisy(p, 1000, 5), b = noisy(p, 1000, 5), c = noisy(p, 1000, 6);
  bool differs = false;
  for (int64_t k = 0; k < 1200; ++k) {
    REQUIRE(a.field_start(k) == b.field_start(k));
    differs = differs || a.field_start(k) != c.field_start(k);
  }
  CHECK(differs);
  CHECK(a.field_start(0) == Time::us(250));  // field 0 keeps the clock's phase
  const RasterTiming steady(raster_60(), Time::us(250));
  CHECK(steady.clock_noise() == nullptr);
}
