#include "latsim/stats/tick_run.hpp"

#include <stdexcept>

namespace latsim::stats {

namespace {

// a / b for a >= 0, b > 0: a 64-bit division when both fit (the usual case),
// instead of a call into the 128-bit division routine.
inline i128 quotient(i128 a, i128 b) {
  if (((a | b) >> 63) == 0) return static_cast<i128>(static_cast<uint64_t>(a) / static_cast<uint64_t>(b));
  return a / b;
}

int64_t to_ticks(i128 v) {
  if (v > static_cast<i128>(INT64_MAX) || v < static_cast<i128>(INT64_MIN))
    throw des::TimeOverflow("tick run value out of the int64 picosecond range");
  return static_cast<int64_t>(v);
}

bool fits64(i128 v) { return v == static_cast<i128>(static_cast<int64_t>(v)); }

i128 checked_mul(i128 a, i128 b) {
  // Two factors within +-2^63 cannot overflow: one plain multiply instead of
  // the overflow-checking routine (the usual case, on every bucket of a run).
  if (fits64(a) && fits64(b)) return a * b;
  i128 r = 0;
  if (__builtin_mul_overflow(a, b, &r)) throw des::TimeOverflow("tick run arithmetic exceeds 128 bits");
  return r;
}

// offset + i * step, the numerator of value i.
i128 offset_at(const TickRun& run, uint64_t i) { return run.offset + checked_mul(static_cast<i128>(i), run.step); }

// Sums over i = 0..n of f_i = floor((a i + b) / c), of i f_i and of f_i^2, for
// a, b >= 0, c > 0, n >= 0: the classic floor-sum recursion, which swaps the
// roles of a and c like Euclid's algorithm and so takes O(log c) steps. The
// intermediate terms stay within a small power of the final sums (<= n^3 when
// a, b < c), far inside 128 bits for the run lengths allowed here.
struct FloorSums {
  i128 f = 0, g = 0, h = 0;
};

FloorSums floor_sums(i128 a, i128 b, i128 c, i128 n) {
  // n <= 2^20 throughout (each swap only shrinks it), so these fit 64 bits.
  const auto n64 = static_cast<uint64_t>(n);
  const auto s1 = static_cast<i128>(n64 * (n64 + 1) / 2);                // sum of i
  const auto s2 = static_cast<i128>(n64 * (n64 + 1) * (2 * n64 + 1) / 6);  // sum of i^2
  if (a == 0) {
    const i128 t = quotient(b, c);
    return {(n + 1) * t, t * s1, (n + 1) * t * t};
  }
  if (a >= c || b >= c) {
    const i128 qa = quotient(a, c), qb = quotient(b, c);
    const FloorSums r = floor_sums(a - qa * c, b - qb * c, c, n);
    return {r.f + qa * s1 + qb * (n + 1), r.g + qa * s2 + qb * s1,
            r.h + 2 * qb * r.f + 2 * qa * r.g + qa * qa * s2 + qb * qb * (n + 1) + 2 * qa * qb * s1};
  }
  const i128 m = quotient(a * n + b, c);
  if (m == 0) return {};
  const FloorSums r = floor_sums(c, c - b - 1, a, m - 1);
  FloorSums out;
  out.f = n * m - r.f;
  out.g = (m * n * (n + 1) - r.h - r.f) >> 1;  // even by construction
  out.h = n * m * (m + 1) - 2 * r.g - 2 * r.f - out.f;
  return out;
}

}  // namespace

TickRun TickRun::make(int64_t base, i128 offset, i128 step, i128 den, uint64_t count) {
  if (den <= 0 || step < 0 || offset < 0)
    throw std::invalid_argument("TickRun: needs den > 0, step >= 0 and offset >= 0");
  TickRun r;
  r.base = to_ticks(static_cast<i128>(base) + offset / den);
  r.offset = offset % den;
  r.step = step;
  r.den = den;
  r.count = count;
  return r;
}

int64_t TickRun::at(uint64_t i) const {
  return to_ticks(static_cast<i128>(base) + quotient(offset_at(*this, i), den));
}

uint64_t TickRun::first_index_at_or_above(int64_t threshold) const {
  const i128 d = static_cast<i128>(threshold) - base;
  if (d <= 0 || count == 0) return 0;  // v_0 = base already reaches it
  if (step == 0) return count;
  // v_i >= threshold  <=>  offset + i step >= d den  <=>  i >= (d den - offset) / step.
  const i128 need = checked_mul(d, den) - offset;
  const i128 i = quotient(need + step - 1, step);
  return i >= static_cast<i128>(count) ? count : static_cast<uint64_t>(i);
}

TickRun TickRun::shifted(int64_t delta) const {
  TickRun r = *this;
  r.base = to_ticks(static_cast<i128>(base) + delta);
  return r;
}

TickRun TickRun::slice(uint64_t begin, uint64_t n) const {
  return make(base, offset + checked_mul(static_cast<i128>(begin), step), step, den, n);
}

TickStepper::TickStepper(const TickRun& run)
    : ticks_(run.base), remainder_(run.offset), den_(run.den) {
  const i128 whole = quotient(run.step, run.den);
  whole_ = to_ticks(whole);
  fraction_ = run.step - whole * run.den;
}

TickStepper::TickStepper(const TickRun& run, uint64_t i) : TickStepper(run) {
  const i128 position = offset_at(run, i);
  const i128 whole = quotient(position, run.den);
  ticks_ = to_ticks(static_cast<i128>(run.base) + whole);
  remainder_ = position - whole * run.den;
}

const TickRunSums& TickRunSumsCache::sums(const TickRun& run) {
  const auto key = static_cast<uint64_t>(run.offset) * 0x9E3779B97F4A7C15ull ^ run.count;
  Entry& e = table_[(key >> 20) % kSize];
  if (e.offset != run.offset || e.step != run.step || e.den != run.den || e.count != run.count) {
    e.sums = tick_run_sums(run);
    e.offset = run.offset;
    e.step = run.step;
    e.den = run.den;
    e.count = run.count;
  }
  return e.sums;
}

TickRunSums tick_run_sums(const TickRun& run) {
  if (run.count > (uint64_t{1} << 20)) throw std::invalid_argument("tick_run_sums: at most 2^20 values at a time");
  TickRunSums out;
  if (run.count == 0) return out;
  // w_i = q i + floor((r i + offset) / den) with 0 <= r, offset < den.
  const i128 q = quotient(run.step, run.den), r = run.step - q * run.den;
  const uint64_t n = run.count - 1;
  const FloorSums fs = floor_sums(r, run.offset, run.den, static_cast<i128>(n));
  const auto sum_i = static_cast<i128>(n * (n + 1) / 2), sum_i2 = static_cast<i128>(n * (n + 1) * (2 * n + 1) / 6);
  out.sum = static_cast<u128>(checked_mul(q, sum_i) + fs.f);
  out.sum_sq = U256::product(static_cast<u128>(q) * static_cast<u128>(q), static_cast<u128>(sum_i2))
                   .plus(U256::product(static_cast<u128>(2 * q), static_cast<u128>(fs.g)))
                   .plus(U256::of(static_cast<u128>(fs.h)));
  return out;
}

TickRunMoments tick_run_moments(const TickRun& run, const TickRunSums& s) {
  TickRunMoments m;
  if (run.count == 0) return {true, 0, 0};
  if (!(s.sum_sq.w[2] == 0 && s.sum_sq.w[3] == 0) || (s.sum >> 126) != 0) return m;
  const u128 n = run.count;
  const bool negative = run.base < 0;
  const u128 b = negative ? u128{0} - static_cast<u128>(static_cast<i128>(run.base)) : static_cast<u128>(run.base);
  const u128 sum_w_sq = static_cast<u128>(s.sum_sq.w[1]) << 64 | s.sum_sq.w[0];
  // |n base| < 2^84 and sum w < 2^126: the sum cannot overflow.
  m.sum = (negative ? -static_cast<i128>(n * b) : static_cast<i128>(n * b)) + static_cast<i128>(s.sum);
  // b^2 < 2^126 (b <= 2^63); the rest is checked.
  u128 n_b2 = 0, cross = 0, squares = 0;
  if (__builtin_mul_overflow(b * b, n, &n_b2) || __builtin_mul_overflow(2 * b, s.sum, &cross) ||
      __builtin_add_overflow(n_b2, sum_w_sq, &squares))
    return m;
  if (negative) {
    m.sum_sq = squares - cross;  // the sum of (base + w_i)^2 >= 0, so no wrap
  } else if (__builtin_add_overflow(squares, cross, &m.sum_sq)) {
    return m;
  }
  m.fits = true;
  return m;
}

}  // namespace latsim::stats
