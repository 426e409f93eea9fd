// Exact sums, closed-form runs and the bit-pattern histogram, each against an
// independent reference: brute-force loops, hand-derived rationals, and a
// floating-point error bound for rounded inputs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "latsim/des/random.hpp"
#include "latsim/stats/stats.hpp"
#include "latsim/stats/tick_run.hpp"

using latsim::stats::Distribution;
using latsim::stats::i128;
using latsim::stats::LogHistogram;
using latsim::des::RandomStream;
using latsim::stats::RunningStats;
using latsim::stats::TickRun;
using latsim::stats::tick_run_sums;
using latsim::stats::TickStepper;
using latsim::des::Time;
using latsim::stats::U256;

namespace {

// A uniform integer in [lo, hi].
int64_t between(RandomStream& rng, int64_t lo, int64_t hi) {
  return lo + static_cast<int64_t>(rng.uniform_int(static_cast<uint64_t>(hi - lo) + 1));
}

// Bit-for-bit equality of every moment (== would also accept -0.0 for 0.0).
void check_same_bits(const RunningStats& a, const RunningStats& b) {
  CHECK(a.count() == b.count());
  CHECK(std::bit_cast<uint64_t>(a.mean()) == std::bit_cast<uint64_t>(b.mean()));
  CHECK(std::bit_cast<uint64_t>(a.variance()) == std::bit_cast<uint64_t>(b.variance()));
  CHECK(std::bit_cast<uint64_t>(a.sum()) == std::bit_cast<uint64_t>(b.sum()));
  CHECK(a.min() == b.min());
  CHECK(a.max() == b.max());
}

TickRun random_run(RandomStream& rng, bool huge_den) {
  const auto den = huge_den ? (static_cast<i128>(between(rng, 1, INT64_MAX / 2)) << 30) + between(rng, 1, 1000)
                            : static_cast<i128>(between(rng, 1, 100'000'000));
  const i128 step = den * between(rng, 0, 50'000) + static_cast<i128>(rng.uniform01() * static_cast<double>(den));
  const i128 offset = static_cast<i128>(rng.uniform01() * static_cast<double>(den)) + den * between(rng, 0, 3);
  const int64_t base = between(rng, -2'000'000'000'000, 2'000'000'000'000);
  return TickRun::make(base, offset, step, den, static_cast<uint64_t>(between(rng, 1, 3000)));
}

}  // namespace

TEST_CASE("tick runs: values, inverse and stepping agree with the direct formula", "[stats][tick_run]") {
  // 59.94 Hz, 640 + 160 pixel times of 480 + 22 lines: pixel slot s is lit at
  // floor(s * 1001e12 / (60000 * 502 * 800)) ps after the retrace.
  const i128 den = i128{60000} * 502 * 800, per_px = i128{1001} * 1'000'000'000'000;
  const TickRun line = TickRun::make(0, 22 * 800 * per_px, per_px, den, 640);
  for (uint64_t i = 0; i < 640; ++i)
    CHECK(line.at(i) == static_cast<int64_t>((22 * 800 + static_cast<i128>(i)) * per_px / den));
  for (const int64_t t : {line.at(0), line.at(0) + 1, line.at(17) - 1, line.at(17), line.at(639), line.at(639) + 1}) {
    const uint64_t i = line.first_index_at_or_above(t);
    INFO("t = " << t << ", i = " << i);
    if (i < line.count) CHECK(line.at(i) >= t);
    if (i > 0) CHECK(line.at(i - 1) < t);
  }
  // Stepping a million pixel times (almost a minute of scanout at one sample
  // per 41.7 ns... of one long run) lands exactly on the direct formula.
  const TickRun long_run = TickRun::make(123, 7 * per_px, 3 * per_px, den, 1'000'000);
  TickStepper s(long_run);
  bool all_equal = true;
  for (uint64_t i = 0; i < long_run.count; ++i, s.step()) all_equal = all_equal && s.ticks() == long_run.at(i);
  CHECK(all_equal);
  CHECK(long_run.slice(500'000, 10).at(3) == long_run.at(500'003));
  CHECK_THROWS_AS(TickRun::make(0, 0, -1, 1, 1), std::invalid_argument);
  CHECK_THROWS_AS(TickRun::make(0, 0, 1, 0, 1), std::invalid_argument);
}

TEST_CASE("tick run sums in closed form equal brute-force sums", "[stats][tick_run]") {
  RandomStream rng(11, "stats.tick_sums");
  for (int trial = 0; trial < 400; ++trial) {
    const TickRun run = random_run(rng, trial % 2 == 1);
    latsim::stats::u128 sum = 0;
    U256 sum_sq;
    for (uint64_t i = 0; i < run.count; ++i) {
      const auto w = static_cast<latsim::stats::u128>(run.at(i) - run.base);
      sum += w;
      sum_sq = sum_sq.plus(U256::of(w * w));
    }
    const auto closed = tick_run_sums(run);
    INFO("trial " << trial << ", count " << run.count);
    CHECK(closed.sum == sum);
    CHECK(closed.sum_sq.w == sum_sq.w);
  }
}

TEST_CASE("RunningStats is exact: order and grouping change no bit", "[stats][exact]") {
  RandomStream rng(12, "stats.order");
  std::vector<double> xs;
  for (int i = 0; i < 20'000; ++i) {
    // Magnitudes from 1e-300 to 1e300, both signs: any rounding would show.
    const double x = std::ldexp(rng.uniform(1.0, 2.0), static_cast<int>(between(rng, -990, 990)));
    xs.push_back(rng.uniform01() < 0.5 ? -x : x);
  }
  RunningStats forward, backward, merged, part;
  for (const double x : xs) forward.add(x);
  for (auto it = xs.rbegin(); it != xs.rend(); ++it) backward.add(*it);
  for (size_t i = 0; i < xs.size(); ++i) {
    part.add(xs[i]);
    if (i % 777 == 776) {
      merged.merge(part);
      part = RunningStats{};
    }
  }
  merged.merge(part);
  check_same_bits(forward, backward);
  check_same_bits(forward, merged);
}

TEST_CASE("RunningStats mean and variance are the exact rationals rounded once", "[stats][exact]") {
  // {1e16, 1, -1e16}: exact sum 1 (every running sum in double loses the 1).
  RunningStats cancel;
  for (const double x : {1e16, 1.0, -1e16}) cancel.add(x);
  CHECK(cancel.sum() == 1.0);
  CHECK(cancel.mean() == 1.0 / 3.0);  // division is correctly rounded
  // Sum of squared deviations: (1e16 - 1/3)^2 + (2/3)^2 + (1e16 + 1/3)^2 = 2e32 + 2/3;
  // over n - 1 = 2: 1e32 + 1/3, whose nearest double is that of 1e32.
  CHECK(cancel.variance() == 1e32);

  // 0.5, 0.75, ..., 2.0 (every value a dyadic rational): sum 8.75, mean 1.25,
  // squared deviations 0.0625 * (9 + 4 + 1 + 0 + 1 + 4 + 9) = 1.75, variance 1.75 / 6 = 7/24.
  RunningStats dyadic;
  dyadic.add_arithmetic_run(0.5, 0.25, 7);
  CHECK(dyadic.count() == 7);
  CHECK(dyadic.sum() == 8.75);
  CHECK(dyadic.mean() == 1.25);
  CHECK(dyadic.variance() == 7.0 / 24.0);
  CHECK(dyadic.min() == 0.5);
  CHECK(dyadic.max() == 2.0);

  // The exact run d, 2d, ..., 10d of d = double(0.1): mean 5.5 d exactly, one rounding.
  RunningStats tenths;
  tenths.add_arithmetic_run(0.1, 0.1, 10);
  CHECK(tenths.mean() == 5.5 * 0.1);

  // Integers beyond 2^53 are summed exactly: (2^62 + 1) + (2^62 + 3) = 2^63 + 4, mean 2^62 + 2.
  RunningStats big;
  big.add_integer((int64_t{1} << 62) + 1);
  big.add_integer((int64_t{1} << 62) + 3);
  CHECK(big.mean() == std::ldexp(1.0, 62));  // 2^62 + 2 rounds to 2^62 (ulp 1024)
  CHECK(big.variance() == 2.0);              // ((-1)^2 + 1^2) / 1
  RunningStats negative;
  negative.add_integer(INT64_MIN);
  negative.add_integer(INT64_MIN);
  CHECK(negative.mean() == -std::ldexp(1.0, 63));
  CHECK(negative.variance() == 0.0);
}

TEST_CASE("a tick run added in closed form equals the loop of single adds, bit for bit", "[stats][tick_run]") {
  RandomStream rng(13, "stats.run_vs_loop");
  for (int trial = 0; trial < 200; ++trial) {
    const TickRun run = random_run(rng, trial % 3 == 0);
    Distribution batch, loop;
    batch.add_run(run);
    for (uint64_t i = 0; i < run.count; ++i) loop.add(Time::ps(run.at(i)));
    INFO("trial " << trial);
    check_same_bits(batch.stats(), loop.stats());
    CHECK(batch.histogram().buckets() == loop.histogram().buckets());
    CHECK(batch.summary().p50 == loop.summary().p50);
  }
  // A run longer than one closed-form chunk (2^20 values) and one crossing zero.
  const TickRun long_run = TickRun::make(-3'000'000'000, 5, 2'083'333, 500, 1'500'000);
  RunningStats batch, loop;
  batch.add_run(long_run);
  TickStepper s(long_run);
  for (uint64_t i = 0; i < long_run.count; ++i, s.step()) loop.add_integer(s.ticks());
  check_same_bits(batch, loop);
}

TEST_CASE("an arithmetic run is exact; a loop of rounded adds is within its error bound", "[stats][exact]") {
  RandomStream rng(14, "stats.arith");
  for (int trial = 0; trial < 100; ++trial) {
    const double first = rng.uniform(-100.0, 100.0), step = rng.uniform(-0.5, 0.5);
    const auto n = static_cast<uint64_t>(between(rng, 2, 5000));
    RunningStats run, loop;
    run.add_arithmetic_run(first, step, n);
    // Each looped value x_i = fl(first + fl(i step)) is off the exact one by at
    // most eps_i = u (|i step| + |x_i|) (1 + u), u = 2^-53: the error of the
    // product and of the sum. The mean then differs by at most sum(eps_i) / n,
    // the variance by (2 sum |x_i - m| eps_i + sum eps_i^2) / (n - 1), plus the
    // final rounding of each result (one ulp of each).
    const double u = std::ldexp(1.0, -53);
    double sum_eps = 0, sum_dev_eps = 0, sum_eps2 = 0;
    const double m = first + step * static_cast<double>(n - 1) / 2;
    for (uint64_t i = 0; i < n; ++i) {
      const double x = first + static_cast<double>(i) * step;
      loop.add(x);
      const double eps = u * (std::fabs(static_cast<double>(i) * step) + std::fabs(x)) * (1 + u);
      sum_eps += eps;
      sum_dev_eps += std::fabs(x - m) * eps;
      sum_eps2 += eps * eps;
    }
    const double ulp_mean = std::ldexp(1.0, std::ilogb(std::fabs(run.mean()) + 1e-300) - 52);
    const double ulp_var = std::ldexp(1.0, std::ilogb(run.variance()) - 52);
    INFO("trial " << trial << ", n " << n);
    CHECK(std::fabs(run.mean() - loop.mean()) <= sum_eps / static_cast<double>(n) * 1.001 + 2 * ulp_mean);
    CHECK(std::fabs(run.variance() - loop.variance()) <=
          (2 * sum_dev_eps + sum_eps2) / static_cast<double>(n - 1) * 1.001 + 2 * ulp_var);
    CHECK(run.count() == loop.count());
    // The histogram holds the rounded values, as the loop does.
    LogHistogram hr, hl;
    hr.add_arithmetic_run(first, step, n);
    for (uint64_t i = 0; i < n; ++i) hl.add(first + static_cast<double>(i) * step);
    CHECK(hr.buckets() == hl.buckets());
    CHECK(hr.min() == hl.min());
    CHECK(hr.max() == hl.max());
  }
  RunningStats empty;
  empty.add_arithmetic_run(1.0, 1.0, 0);
  CHECK(empty.count() == 0);
  CHECK_THROWS_AS(empty.add_arithmetic_run(1e308, 1e308, 3), std::invalid_argument);
}

TEST_CASE("each bucket's representative is within the bound of every value in it", "[stats][histogram]") {
  RandomStream rng(15, "stats.bucket_bound");
  for (const double a : {0.5, 0.1, 0.01, 0.005, 0.001, 1e-4}) {
    const LogHistogram probe(a, 1e-300);
    const double bound = 1.0 / (2.0 * probe.buckets_per_binade() + 1.0);
    CHECK(bound < a);
    double worst = 0;
    for (int i = 0; i < 20'000; ++i) {
      // Random values, values just below and at powers of two, and their neighbours.
      double x = std::ldexp(rng.uniform(1.0, 2.0), static_cast<int>(between(rng, -900, 900)));
      if (i % 4 == 1) x = std::ldexp(1.0, static_cast<int>(between(rng, -900, 900)));
      if (i % 4 == 2) x = std::nextafter(x, 0.0);
      if (i % 4 == 3) x = std::nextafter(std::ldexp(1.0, static_cast<int>(between(rng, -900, 900))), 0.0);
      LogHistogram h(a, 1e-300);
      h.add(x);
      const double rep = h.buckets().front().first;
      worst = std::max(worst, std::fabs(rep - x) / x);
    }
    INFO("relative_error " << a << ", worst " << worst);
    CHECK(worst <= bound * (1 + 1e-12));
  }
  CHECK_THROWS_AS(LogHistogram(0.01, 1e-320), std::invalid_argument);
  // The largest finite double has a finite representative.
  LogHistogram top;
  top.add(std::numeric_limits<double>::max());
  CHECK(std::isfinite(top.buckets().front().first));
}

TEST_CASE("durations are kept in picoseconds and reported in milliseconds", "[stats]") {
  Distribution d(0.005, true);
  d.add(Time::ms(16));
  d.add(Time::ps(1));
  d.add(Time::us(500));
  const auto s = d.summary();
  CHECK(d.holds_durations());
  CHECK(d.unit() == 1e-9);
  CHECK(s.count == 3);
  CHECK(s.max == Time::ms(16).to_ms());
  CHECK(s.min == Time::ps(1).to_ms());
  // Mean of 16e9 + 1 + 5e8 ps = 16500000001 / 3 ps, rounded, then scaled to ms.
  CHECK(s.mean == (16'500'000'001.0 / 3.0) * 1e-9);
  CHECK(d.quantile(0.5) == Time::us(500).to_ms());
  CHECK_THROWS_AS(d.add(2.5), std::logic_error);
  Distribution plain;
  plain.add(1.0);
  CHECK_THROWS_AS(plain.add(Time::ms(1)), std::logic_error);
  CHECK_THROWS_AS(plain.merge(d), std::logic_error);
  CHECK(plain.count() == 1);
  Distribution empty;
  empty.merge(d);
  CHECK(empty.holds_durations());
  CHECK(empty.count() == 3);
}

TEST_CASE("a run's moments are 128-bit integers while they fit, and the wide sums take them past that",
          "[stats][tick_run]") {
  // Second method: the sums of v_i and v_i^2 from the values themselves, in
  // 256 bits.
  const auto direct = [](const TickRun& run, i128& sum, U256& sum_sq) {
    sum = 0;
    sum_sq = U256{};
    for (uint64_t i = 0; i < run.count; ++i) {
      const int64_t v = run.at(i);
      sum += v;
      const auto m = static_cast<latsim::stats::u128>(v < 0 ? -static_cast<i128>(v) : static_cast<i128>(v));
      sum_sq = sum_sq.plus(U256::product(m, m));
    }
  };
  RandomStream rng(15, "stats.run_moments");
  for (int trial = 0; trial < 200; ++trial) {
    // |base| <= 2e12 and n <= 3000: n base^2 <= 1.2e28, far below 2^127; the
    // other terms are smaller still, so the moments must fit.
    const TickRun run = random_run(rng, trial % 3 == 0);
    const latsim::stats::TickRunMoments m = latsim::stats::tick_run_moments(run, tick_run_sums(run));
    i128 sum = 0;
    U256 sum_sq;
    direct(run, sum, sum_sq);
    INFO("trial " << trial);
    REQUIRE(m.fits);
    CHECK(m.sum == sum);
    CHECK(static_cast<uint64_t>(m.sum_sq) == sum_sq.w[0]);
    CHECK(static_cast<uint64_t>(m.sum_sq >> 64) == sum_sq.w[1]);
    CHECK((sum_sq.w[2] | sum_sq.w[3]) == 0);
  }
  // Values near +-2^62: a thousand squares pass 2^128, so the run goes to the
  // wide sums, and still equals its values added one by one.
  for (const int64_t base : {int64_t{1} << 62, -(int64_t{1} << 62) - 5'000'000}) {
    const TickRun run = TickRun::make(base, 7, 3'000'001, 1'000, 1'000);
    CHECK_FALSE(latsim::stats::tick_run_moments(run, tick_run_sums(run)).fits);
    RunningStats batch, loop;
    batch.add_run(run);
    batch.add_run(run.slice(0, 10));  // a short one that fits, after the wide one
    for (int pass = 0; pass < 2; ++pass)
      for (uint64_t i = 0; i < (pass == 0 ? run.count : 10); ++i) loop.add_integer(run.at(i));
    INFO("base " << base);
    check_same_bits(batch, loop);
  }
}
