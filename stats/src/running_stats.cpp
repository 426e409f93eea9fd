#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "finite_sample.hpp"
#include "latsim/stats/stats.hpp"

namespace latsim::stats {

namespace {

// x = (negative ? -1 : 1) * mantissa * 2^exponent with an integer mantissa.
struct Decomposed {
  uint64_t mantissa;
  int exponent;
  bool negative;
};

Decomposed decompose(double x) {
  const auto bits = std::bit_cast<uint64_t>(x);
  const auto biased = static_cast<int>((bits >> 52) & 0x7FF);
  const uint64_t fraction = bits & ((uint64_t{1} << 52) - 1);
  if (biased == 0) return {fraction, -1074, (bits >> 63) != 0};  // zero or subnormal
  return {fraction | (uint64_t{1} << 52), biased - 1075, (bits >> 63) != 0};
}

uint64_t magnitude_of(int64_t v) { return v < 0 ? uint64_t{0} - static_cast<uint64_t>(v) : static_cast<uint64_t>(v); }

}  // namespace

uint64_t nearest_rank_index(double q, uint64_t n) {
  if (!(q >= 0.0 && q <= 1.0)) {
    throw std::invalid_argument("quantile: q must be in [0, 1], got " + std::to_string(q));
  }
  if (n == 0) throw std::invalid_argument("quantile: no values");
  const double rank = std::ceil(q * static_cast<double>(n));
  if (rank <= 1.0) return 0;
  const auto k = static_cast<uint64_t>(rank) - 1;
  return std::min(k, n - 1);
}

void RunningStats::fold(__int128 int_sum, u128 int_sum_sq, Sum& sum, SumOfSquares& sum_sq) {
  const bool negative = int_sum < 0;
  const u128 magnitude = negative ? u128{0} - static_cast<u128>(int_sum) : static_cast<u128>(int_sum);
  sum.add(U256::of(magnitude), 0, negative);
  sum_sq.add(U256::of(int_sum_sq), 0, false);
}

void RunningStats::spill_integers() {
  fold(int_sum_, int_sum_sq_, sum_, sum_sq_);
  int_sum_ = 0;
  int_sum_sq_ = 0;
}

RunningStats::Sum RunningStats::total_sum() const {
  Sum s = sum_;
  SumOfSquares unused;
  fold(int_sum_, 0, s, unused);
  return s;
}

RunningStats::SumOfSquares RunningStats::total_sum_sq() const {
  Sum unused;
  SumOfSquares s = sum_sq_;
  fold(0, int_sum_sq_, unused, s);
  return s;
}

void RunningStats::add(double x) {
  require_finite(x, "RunningStats::add");
  seen_.note(x, x, 1);
  const Decomposed d = decompose(x);
  if (d.mantissa == 0) return;
  sum_.add(d.mantissa, d.exponent, d.negative);
  add_square(static_cast<u128>(d.mantissa) * d.mantissa, 2 * d.exponent);
}

void RunningStats::add_run(const TickRun& run) {
  constexpr uint64_t kChunk = uint64_t{1} << 20;
  for (uint64_t begin = 0; begin < run.count; begin += kChunk) {
    const TickRun part = run.count <= kChunk ? run : run.slice(begin, std::min(kChunk, run.count - begin));
    add_run(part, tick_run_sums(part));
  }
}

void RunningStats::add_run(const TickRun& run, const TickRunSums& s, int64_t last, const TickRunMoments& moments) {
  if (run.count == 0) return;
  if (moments.fits) {
    add_integer_sums(moments.sum, moments.sum_sq);
    seen_.note(static_cast<double>(run.base), static_cast<double>(last), run.count);
    return;
  }
  // v_i = base + w_i: sum = n base + sum w, sum of squares = n base^2 + 2 base sum w + sum w^2.
  const uint64_t n = run.count, b = magnitude_of(run.base);
  const bool negative = run.base < 0;
  sum_.add(U256::of(static_cast<u128>(b) * n), 0, negative);
  sum_.add(U256::of(s.sum), 0, false);
  sum_sq_.add(U256::product(static_cast<u128>(b) * b, n), 0, false);
  sum_sq_.add(U256::product(static_cast<u128>(b) * 2, s.sum), 0, negative);
  sum_sq_.add(s.sum_sq, 0, false);
  seen_.note(static_cast<double>(run.base), static_cast<double>(last), n);
}

void RunningStats::add_arithmetic_run(double first, double step, uint64_t n) {
  require_finite(first, "RunningStats::add_arithmetic_run (first)");
  require_finite(step, "RunningStats::add_arithmetic_run (step)");
  if (n == 0) return;
  if (n > (uint64_t{1} << 32)) throw std::invalid_argument("RunningStats::add_arithmetic_run: at most 2^32 values");
  const double last = first + static_cast<double>(n - 1) * step;
  require_finite(last, "RunningStats::add_arithmetic_run (last value)");
  // x_i = a + i d: sum = n a + d T1, sum of squares = n a^2 + 2 a d T1 + d^2 T2
  // with T1 = sum of i = n(n-1)/2 and T2 = sum of i^2 = (n-1)n(2n-1)/6.
  const Decomposed a = decompose(first), d = decompose(step);
  const u128 t1 = static_cast<u128>(n) * (n - 1) / 2;
  const u128 t2 = static_cast<u128>(n - 1) * n * (2 * static_cast<u128>(n) - 1) / 6;
  const u128 aa = static_cast<u128>(a.mantissa) * a.mantissa, dd = static_cast<u128>(d.mantissa) * d.mantissa;
  sum_.add(U256::of(static_cast<u128>(a.mantissa) * n), a.exponent, a.negative);
  sum_.add(U256::of(static_cast<u128>(d.mantissa) * t1), d.exponent, d.negative);
  sum_sq_.add(U256::product(aa, n), 2 * a.exponent, false);
  sum_sq_.add(U256::product(static_cast<u128>(a.mantissa) * d.mantissa * 2, t1), a.exponent + d.exponent,
              a.negative != d.negative);
  sum_sq_.add(U256::product(dd, t2), 2 * d.exponent, false);
  seen_.note(std::min(first, last), std::max(first, last), n);
}

double RunningStats::mean() const {
  if (seen_.count == 0) return 0.0;
  bool negative = false;
  BigUint total = total_sum().magnitude(negative);
  const uint64_t remainder = total.divide(seen_.count);
  return total.to_double(Sum::min_exponent(), negative, remainder != 0);
}

double RunningStats::variance() const {
  if (seen_.count < 2) return 0.0;
  // (n sum x^2 - (sum x)^2) / (n (n - 1)), exactly, then rounded once. Both
  // terms are in units of 2^-2148 (the square of sum x's unit).
  bool negative = false, ignored = false;
  const BigUint s = total_sum().magnitude(negative);
  const BigUint scaled_squares = total_sum_sq().magnitude(ignored).times(seen_.count);
  const BigUint square_of_sum = s.times(s);
  if (!square_of_sum.less_than(scaled_squares)) return 0.0;  // all values equal
  BigUint numerator = scaled_squares.minus(square_of_sum);
  const uint64_t r1 = numerator.divide(seen_.count);
  const uint64_t r2 = numerator.divide(seen_.count - 1);  // floor(floor(a/b)/c) = floor(a/(bc))
  return numerator.to_double(SumOfSquares::min_exponent(), false, r1 != 0 || r2 != 0);
}

double RunningStats::stddev() const { return std::sqrt(variance()); }

double RunningStats::sum() const {
  bool negative = false;
  return total_sum().magnitude(negative).to_double(Sum::min_exponent(), negative, false);
}

void RunningStats::merge(const RunningStats& other) {
  if (other.seen_.count == 0) return;
  seen_.note(other.seen_.min, other.seen_.max, other.seen_.count);
  sum_.merge(other.total_sum());
  sum_sq_.merge(other.total_sum_sq());
}

}  // namespace latsim::stats
