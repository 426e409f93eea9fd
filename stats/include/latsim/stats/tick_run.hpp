// Evenly spaced instants on the picosecond grid, and stepping through them.
//
// The photon times of the pixels of a line, or of the lines of a field, are
// t_i = base + floor((offset + i * step) / den) ticks: an arithmetic run whose
// exact rational step (for example 1/(60 * 502 * 800) s per pixel) is floored
// to whole picoseconds. TickRun describes such a run so that statistics can be
// taken over it in closed form; TickStepper walks it one index at a time with
// an exact remainder instead of a division per step.
#pragma once

#include <cstdint>
#include <vector>

#include "latsim/stats/exact_sum.hpp"
#include "latsim/stats/reused_table.hpp"
#include "latsim/des/time.hpp"

namespace latsim::stats {

using i128 = __int128;

/// count values v_i = base + floor((offset + i * step) / den), i in [0, count),
/// with den > 0, step >= 0 and (after make()) 0 <= offset < den.
struct TickRun {
  int64_t base = 0;
  i128 offset = 0;
  i128 step = 0;
  i128 den = 1;
  uint64_t count = 0;

  /// A normalised run; throws std::invalid_argument unless den > 0, step >= 0
  /// and offset >= 0, TimeOverflow if base moves out of the int64 range.
  static TickRun make(int64_t base, i128 offset, i128 step, i128 den, uint64_t count);
  /// A single value.
  static TickRun single(int64_t value) { return TickRun{value, 0, 0, 1, 1}; }

  /// v_i (one division).
  int64_t at(uint64_t i) const;
  int64_t first() const { return base; }
  int64_t last() const { return at(count - 1); }
  /// The smallest i with v_i >= threshold, or count if there is none.
  uint64_t first_index_at_or_above(int64_t threshold) const;
  /// The same run with every value moved by delta ticks.
  TickRun shifted(int64_t delta) const;
  /// Values [begin, begin + n) as a run of their own.
  TickRun slice(uint64_t begin, uint64_t n) const;
};

/// Walks the instants of a TickRun in order: each step adds the whole ticks
/// of the step and carries the exact remainder, so index i lands exactly on
/// TickRun::at(i) however far it goes, without dividing.
class TickStepper {
 public:
  TickStepper() = default;
  explicit TickStepper(const TickRun& run);
  /// At index i of `run` (one division).
  TickStepper(const TickRun& run, uint64_t i);
  des::Time time() const { return des::Time::ps(ticks_); }
  int64_t ticks() const { return ticks_; }
  /// The exact fraction of a tick past ticks(), in units of 1/den, in [0, den).
  i128 remainder() const { return remainder_; }
  void step() {
    ticks_ += whole_;
    remainder_ += fraction_;
    if (remainder_ >= den_) {
      remainder_ -= den_;
      ++ticks_;
    }
  }
  /// The run of `count` instants from this position on, `step / den` ticks
  /// apart (den of this stepper's run).
  TickRun run_from_here(i128 step, uint64_t count) const { return TickRun{ticks_, remainder_, step, den_, count}; }
  /// This position, stepping from now on at the pace of `pace` (a stepper
  /// over a run with the same den): no division.
  TickStepper at_pace_of(const TickStepper& pace) const {
    TickStepper s = *this;
    s.whole_ = pace.whole_;
    s.fraction_ = pace.fraction_;
    return s;
  }

 private:
  int64_t ticks_ = 0;
  int64_t whole_ = 0;
  i128 fraction_ = 0;
  i128 remainder_ = 0;
  i128 den_ = 1;
};

/// Exact sums over a TickRun: sum of (v_i - base) and of (v_i - base)^2.
struct TickRunSums {
  u128 sum = 0;  ///< sum of w_i = v_i - base
  U256 sum_sq;   ///< sum of w_i^2
};
/// Closed form in O(log den) (a floor-sum recursion); count must be at most 2^20.
TickRunSums tick_run_sums(const TickRun& run);

/// The sum of a run's values v_i and of their squares as 128-bit integers,
/// when both fit (runs of durations of a second or less always do).
struct TickRunMoments {
  bool fits = false;
  i128 sum = 0;
  u128 sum_sq = 0;
};
/// From the run's sums (tick_run_sums(run)): sum = n base + sum w and sum of
/// squares = n base^2 + 2 base sum w + sum w^2; `fits` is false when either
/// needs more than 128 bits on the way.
TickRunMoments tick_run_moments(const TickRun& run, const TickRunSums& s);

/// Remembers tick_run_sums() of recent runs: the sums depend only on a run's
/// offset, step, den and count, and the lines of a raster repeat the same few
/// offsets field after field, so a small table answers most requests.
class TickRunSumsCache {
 public:
  const TickRunSums& sums(const TickRun& run);

 private:
  static constexpr size_t kSize = 4096;  // the lines of a few fields (see RunBucketsCache)
  struct Entry {
    i128 offset = -1, step = 0, den = 0;
    uint64_t count = 0;
    TickRunSums sums;
  };
  // Reused from run to run: an entry is its key's sums whoever left it.
  ReusedTable<Entry, kSize> table_;
};

}  // namespace latsim::stats
