// Streaming statistics that models emit samples into and summaries read from.
//
// Every add() rejects non-finite input (NaN, +-inf) with std::invalid_argument:
// such a sample is a model bug, and it would silently poison every moment.
// Empty containers report 0 for every statistic, so summaries are NaN-free.
//
// Moments are kept as exact sums, so they do not depend on the order in which
// values arrive or on how they are grouped: a run of values added in closed
// form (all lines of a field, all pixels of a line) gives the same bits as the
// same values added one by one, and a merge gives the same bits as one stream.
//
// Quantile definition used throughout (nearest rank): for q in [0, 1] and n
// values sorted ascending x_0 <= ... <= x_{n-1}, quantile(q) = x_k with
// k = nearest_rank_index(q, n) = max(0, ceil(q * n) - 1); q = 0 gives the
// minimum, q = 1 the maximum.
#pragma once

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "latsim/stats/exact_sum.hpp"
#include "latsim/stats/tick_run.hpp"
#include "latsim/des/time.hpp"

namespace latsim::stats {

/// The 0-based index of the nearest-rank q-quantile among n sorted values;
/// throws std::invalid_argument unless q is in [0, 1] and n > 0.
uint64_t nearest_rank_index(double q, uint64_t n);

/// How many values a stream had and its exact extremes (shared by the
/// statistics below).
struct Extremes {
  uint64_t count = 0;
  double min = 0.0;
  double max = 0.0;

  /// n values, the smallest lo and the largest hi.
  void note(double lo, double hi, uint64_t n) {
    if (count == 0) [[unlikely]] {
      min = lo;
      max = hi;
    } else {
      min = lo < min ? lo : min;
      max = hi > max ? hi : max;
    }
    count += n;
  }
};

/// Count, mean, variance, min and max of a stream of values in O(1) memory.
///
/// The sums of x and of x^2 are exact (fixed-point integers wide enough for
/// any double), so mean() and variance() are the exact results rounded once:
/// no cancellation for values with a large common offset (1e9 + small), no
/// drift over billions of values, and bit-identical results whatever the
/// order, grouping or merging of the same values.
class RunningStats {
 public:
  void add(double x);
  /// Adds an integer exactly (picoseconds, say), also beyond 2^53.
  void add_integer(int64_t v) {
    const double x = static_cast<double>(v);
    seen_.note(x, x, 1);
    // Integers go to 128-bit sums first (a multiply and two adds); the wide
    // sums take them over only when those would overflow, and when read.
    add_integer_sums(v, static_cast<u128>(static_cast<__int128>(v) * v));
  }
  /// Adds every value of a tick run, in closed form.
  void add_run(const TickRun& run);
  /// The same with the run's sums already at hand (tick_run_sums(run), e.g.
  /// from a TickRunSumsCache; run.count <= 2^20).
  void add_run(const TickRun& run, const TickRunSums& sums) { add_run(run, sums, run.last()); }
  /// The same with the run's last value at hand too (run.last(): a division).
  void add_run(const TickRun& run, const TickRunSums& sums, int64_t last) {
    add_run(run, sums, last, tick_run_moments(run, sums));
  }
  /// The same with its moments at hand too (tick_run_moments(run, sums)).
  void add_run(const TickRun& run, const TickRunSums& sums, int64_t last, const TickRunMoments& moments);
  /// Adds the n exact values first + i * step (i in [0, n)) in closed form;
  /// min and max are the end values rounded to double. n is at most 2^32.
  void add_arithmetic_run(double first, double step, uint64_t n);
  uint64_t count() const { return seen_.count; }
  double mean() const;
  /// Sample variance (divisor n - 1); 0 for fewer than two values.
  double variance() const;
  double stddev() const;
  /// Exact extremes; 0 when empty.
  double min() const { return seen_.count == 0 ? 0.0 : seen_.min; }
  double max() const { return seen_.count == 0 ? 0.0 : seen_.max; }
  /// Sum of all values, rounded once.
  double sum() const;
  /// Afterwards this equals the stats of both inputs' values together.
  void merge(const RunningStats& other);

 private:
  // Sum of x in units of 2^-1074 (the smallest subnormal), of x^2 in units of
  // 2^-2148, each with room for 2^64 values of the largest double.
  using Sum = FixedPointSum<-1074, 72>;
  using SumOfSquares = FixedPointSum<-2148, 138>;

  // Adds integer sums of values and of their squares to the 128-bit sums.
  void add_integer_sums(__int128 sum_v, u128 sum_v_sq) {
    u128 sum_sq = 0;
    __int128 sum = 0;
    const bool square_overflows = __builtin_add_overflow(int_sum_sq_, sum_v_sq, &sum_sq);
    const bool sum_overflows = __builtin_add_overflow(int_sum_, sum_v, &sum);
    if (square_overflows || sum_overflows) [[unlikely]] {
      spill_integers();
      int_sum_sq_ = sum_v_sq;
      int_sum_ = sum_v;
    } else {
      int_sum_sq_ = sum_sq;
      int_sum_ = sum;
    }
  }
  void add_square(u128 magnitude_squared, int exponent) {
    sum_sq_.add(static_cast<uint64_t>(magnitude_squared), exponent, false);
    if (const auto high = static_cast<uint64_t>(magnitude_squared >> 64); high != 0)
      sum_sq_.add(high, exponent + 64, false);
  }
  // Moves the 128-bit integer sums into the wide ones.
  void spill_integers();
  static void fold(__int128 int_sum, u128 int_sum_sq, Sum& sum, SumOfSquares& sum_sq);
  // The wide sums with the integer sums folded in (for reading).
  Sum total_sum() const;
  SumOfSquares total_sum_sq() const;

  Extremes seen_;
  __int128 int_sum_ = 0;  // sum of integers added since the last spill
  u128 int_sum_sq_ = 0;   // and of their squares
  Sum sum_;
  SumOfSquares sum_sq_;
};

/// How the values of one tick run fall into the buckets of LogHistograms of
/// one shape: a block of consecutive values per bucket, in value order.
/// Worked out once (LogHistogram::bucket_run), it is added to any histogram
/// of that shape with one increment per bucket (LogHistogram::add_buckets).
struct RunBuckets {
  struct Block {
    int32_t bucket = 0;  // of the magnitude
    uint64_t count = 0;
  };
  TickRun run;
  int64_t last = 0;        // run.last(), worked out once
  int32_t per_binade = 0;  // the shape of the histograms the blocks are for
  double min_positive = 0.0;
  std::vector<Block> negative;  // ascending values: descending buckets
  uint64_t zero = 0;            // values in the zero bucket
  std::vector<Block> positive;  // ascending buckets
};

/// Quantiles with bounded relative error in memory bounded by the value range.
///
/// Buckets split every binade [2^e, 2^(e+1)) into S equal parts, S the
/// smallest count with 1 / (2 S + 1) < relative_error; the bucket of a value
/// comes straight from the exponent and mantissa bits of the double (one
/// multiply, no logarithm), and the representative 2 lo hi / (lo + hi) of a
/// bucket [lo, hi) is within (hi - lo) / (hi + lo) <= 1 / (2 S + 1) of every
/// magnitude in it. Magnitudes below min_positive share one zero bucket
/// (represented by 0); negative values use mirrored buckets. Counts live in
/// dense arrays indexed by bucket, so memory grows with the number of binades
/// the magnitudes span (S per binade, 100 at the default 0.005, plus at most
/// a third for growth slack), never with the number of values.
class LogHistogram {
 public:
  /// relative_error in [1e-4, 0.5] (smaller would make the bucket arrays
  /// huge); min_positive finite and >= DBL_MIN (the smallest normal double).
  /// Throws std::invalid_argument otherwise.
  explicit LogHistogram(double relative_error = 0.005, double min_positive = 1e-9);

  void add(double x) {
    if (!std::isfinite(x)) [[unlikely]] reject_non_finite(x);
    add_to_bucket(x, 1);
    seen_.note(x, x, 1);
  }
  /// Adds x as if it were added `weight` times (weight 0 does nothing).
  void add(double x, uint64_t weight);
  /// Adds every value of a tick run (as doubles), one bucket at a time.
  void add_run(const TickRun& run);
  /// Works out into `out` how the run's values fall into this histogram's
  /// buckets (the walk of add_run), reusing out's memory.
  void bucket_run(const TickRun& run, RunBuckets& out) const;
  /// The same when every value of the run falls into one bucket (`last` is
  /// run.last()): no walk, no division; false, with `out` untouched, when
  /// the run spans more than one bucket or reaches 2^53 (the walk's domain).
  bool bucket_if_one(const TickRun& run, int64_t last, RunBuckets& out) const;
  /// Adds the run of `b` as add_run(b.run) would; throws
  /// std::invalid_argument if b was worked out for another bucket shape.
  void add_buckets(const RunBuckets& b);
  /// True when both histograms put every value into the same bucket.
  bool same_buckets(const LogHistogram& other) const {
    return per_binade_ == other.per_binade_ && min_positive_ == other.min_positive_;
  }
  /// Adds first + i * step for i in [0, n), each rounded to double as a loop
  /// of add() would, one bucket at a time.
  void add_arithmetic_run(double first, double step, uint64_t n);
  uint64_t count() const { return seen_.count; }
  /// Nearest-rank quantile (see file comment), clamped to the exact [min, max]
  /// seen and exactly min / max at the extreme ranks; 0 when empty. Relative
  /// error <= relative_error() for values whose magnitude is >= min_positive.
  double quantile(double q) const;
  /// Exact extremes of the values added; 0 when empty.
  double min() const { return seen_.count == 0 ? 0.0 : seen_.min; }
  double max() const { return seen_.count == 0 ? 0.0 : seen_.max; }
  /// Adds another histogram's counts; both must have the same relative_error
  /// and min_positive (std::invalid_argument otherwise).
  void merge(const LogHistogram& other);
  /// Non-empty buckets as (representative value, count), ascending by value.
  std::vector<std::pair<double, uint64_t>> buckets() const;
  double relative_error() const { return relative_error_; }
  double min_positive() const { return min_positive_; }
  /// Buckets per binade (S above).
  int buckets_per_binade() const { return per_binade_; }
  /// Bucket slots currently allocated (the memory footprint, in counters).
  size_t allocated_buckets() const { return positive_.slots() + negative_.slots(); }

 private:
  // Counts for a contiguous run of bucket indices, grown at either end.
  class DenseCounts {
   public:
    void add(int32_t index, uint64_t weight) {
      const auto slot = static_cast<size_t>(static_cast<int64_t>(index) - offset_);
      if (slot < counts_.size()) [[likely]] {
        counts_[slot] += weight;
        return;
      }
      grow_and_add(index, weight);
    }
    // Adds blocks whose buckets are monotone (either way): one range check.
    void add_blocks(const std::vector<RunBuckets::Block>& blocks);
    uint64_t at(int32_t index) const;
    int32_t first_index() const { return offset_; }
    int32_t end_index() const { return offset_ + static_cast<int32_t>(counts_.size()); }
    size_t slots() const { return counts_.size(); }

   private:
    void grow_and_add(int32_t index, uint64_t weight);
    int32_t offset_ = 0;  // bucket index of counts_[0]
    std::vector<uint64_t> counts_;
  };

  // Bucket of a magnitude >= min_positive (a normal double): S sub-buckets
  // of the binade from the top bits of the fraction, by one multiply.
  int32_t bucket_index(double magnitude) const {
    const auto bits = std::bit_cast<uint64_t>(magnitude);
    const auto exponent = static_cast<int32_t>(bits >> 52);
    const auto sub = static_cast<int32_t>(
        (static_cast<u128>(bits & ((uint64_t{1} << 52) - 1)) * static_cast<u128>(per_binade_)) >> 52);
    return exponent * per_binade_ + sub;
  }
  [[noreturn]] static void reject_non_finite(double x);
  // Smallest magnitude in bucket `index`.
  double bucket_lower(int32_t index) const;
  double representative(int32_t index) const;
  // Bucket value at a 0-based rank in the ascending order of all values.
  double value_at_rank(uint64_t rank) const;
  // Adds n copies of x's bucket without touching min/max/count.
  void add_to_bucket(double x, uint64_t n) {
    const double magnitude = std::fabs(x);
    if (magnitude < min_positive_) [[unlikely]] {
      zero_count_ += n;
    } else if (x > 0.0) {
      positive_.add(bucket_index(magnitude), n);
    } else {
      negative_.add(bucket_index(magnitude), n);
    }
  }
  // The head of `out` for `run`, with no blocks yet.
  void start_buckets(const TickRun& run, int64_t last, RunBuckets& out) const;
  // Appends a block of n values in the bucket of x.
  void add_block(double x, uint64_t n, RunBuckets& out) const;
  // The smallest value above x whose bucket differs from x's bucket.
  double next_bucket_start(double x) const;
  // Calls on_block(x, n) for each block of n consecutive values of the run
  // that share the bucket of value x, in order.
  template <class OnBlock>
  void walk_run(const TickRun& run, OnBlock&& on_block) const;

  double relative_error_;
  double min_positive_;
  int32_t per_binade_;
  std::vector<uint64_t> lower_fraction_;  // first 52-bit fraction of each sub-bucket, and 2^52
  DenseCounts positive_;
  DenseCounts negative_;  // indexed by the bucket of |x|
  uint64_t zero_count_ = 0;
  Extremes seen_;
};

/// A model's output channel for one quantity: RunningStats for moments, a
/// LogHistogram for quantiles, and optionally every exact sample.
///
/// A distribution holds plain numbers or durations, decided by its first
/// sample: durations (add(Time), add_run) are stored as exact picoseconds and
/// reported in milliseconds (unit() = 1e-9); mixing the two throws
/// std::logic_error. stats(), histogram() and samples() are in stored units,
/// summary(), quantile() and plot_histogram() in reported units.
///
/// With keep_samples, up to max_samples values are kept and quantiles are
/// exact; once more than max_samples arrive the samples are released (to
/// bound memory) and keeps_samples() turns false, quantiles then come from
/// the histogram.
class Distribution {
 public:
  explicit Distribution(double relative_error = 0.005, bool keep_samples = false,
                        size_t max_samples = 10'000'000);

  void add(double x);
  /// A duration, kept exactly in picoseconds.
  void add(des::Time t) {
    if (kind_ != Kind::durations) [[unlikely]] {
      check_kind(Kind::durations);
      kind_ = Kind::durations;
    }
    stats_.add_integer(t.ticks());
    const auto x = static_cast<double>(t.ticks());
    histogram_.add(x);
    if (keep_samples_) keep(x);
  }
  /// Every duration of a tick run (picoseconds), moments in closed form.
  void add_run(const TickRun& run);
  /// The same with tick_run_sums(run) at hand (run.count <= 2^20).
  void add_run(const TickRun& run, const TickRunSums& sums);
  /// The same with the run's histogram buckets at hand too (b.run is the run;
  /// see LogHistogram::add_buckets).
  void add_run(const TickRunSums& sums, const RunBuckets& b) { add_run(sums, b, tick_run_moments(b.run, sums)); }
  /// The same with the run's moments at hand (tick_run_moments(b.run, sums)).
  void add_run(const TickRunSums& sums, const RunBuckets& b, const TickRunMoments& moments);
  /// The plain values first + i * step, i in [0, n) (see RunningStats).
  void add_arithmetic_run(double first, double step, uint64_t n);
  uint64_t count() const { return stats_.count(); }
  bool holds_durations() const { return kind_ == Kind::durations; }
  /// Reported value per stored value: 1e-9 (ps to ms) for durations, else 1.
  double unit() const { return kind_ == Kind::durations ? 1e-9 : 1.0; }
  const RunningStats& stats() const { return stats_; }
  const LogHistogram& histogram() const { return histogram_; }
  /// Nearest-rank quantile (see file comment): exact while samples are kept,
  /// otherwise from the histogram; always within [min, max]; 0 when empty.
  double quantile(double q) const;
  /// The kept samples in the order they were added (empty when not kept).
  const std::vector<double>& samples() const { return samples_; }
  /// True while every sample added so far is held.
  bool keeps_samples() const { return keep_samples_; }
  /// Combines both distributions' values; samples stay kept only if both kept
  /// them and together they fit in max_samples (this one's samples first).
  void merge(const Distribution& other);

  struct Summary {
    uint64_t count = 0;
    double mean = 0.0;
    double stddev = 0.0;
    double min = 0.0;
    double p50 = 0.0;
    double p90 = 0.0;
    double p99 = 0.0;
    double p999 = 0.0;
    double max = 0.0;
  };
  /// NaN-free: an empty distribution gives count 0 and zeros.
  Summary summary() const;

  /// Equal-width bins from min to max as (bin lower edge, count); counts sum
  /// to count(). Built from the exact samples when kept, else by placing each
  /// log bucket's count at its representative value. A single bin when
  /// min == max, nothing when empty. Throws std::invalid_argument for bins < 1.
  std::vector<std::pair<double, uint64_t>> plot_histogram(int bins = 50) const;

 private:
  enum class Kind : uint8_t { empty, plain, durations };
  // Throws std::logic_error if values of `kind` cannot join this distribution.
  void check_kind(Kind kind) const;
  void keep(double stored_value);
  // The histogram and kept samples of a run whose moments are added.
  void add_run_samples(const TickRun& run);
  // The kept samples of a run (when samples are kept).
  void add_kept_samples(const TickRun& run);
  void release_samples();

  RunningStats stats_;
  LogHistogram histogram_;
  Kind kind_ = Kind::empty;
  bool keep_samples_;
  size_t max_samples_;
  std::vector<double> samples_;
};

}  // namespace latsim::stats
