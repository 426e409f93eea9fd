// Streaming statistics that models emit samples into and summaries read from.
//
// Every add() rejects non-finite input (NaN, +-inf) with std::invalid_argument:
// such a sample is a model bug, and it would silently poison every moment.
// Empty containers report 0 for every statistic, so summaries are NaN-free.
//
// Quantile definition used throughout (nearest rank): for q in [0, 1] and n
// values sorted ascending x_0 <= ... <= x_{n-1}, quantile(q) = x_k with
// k = nearest_rank_index(q, n) = max(0, ceil(q * n) - 1); q = 0 gives the
// minimum, q = 1 the maximum.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace latsim::des {

/// The 0-based index of the nearest-rank q-quantile among n sorted values;
/// throws std::invalid_argument unless q is in [0, 1] and n > 0.
uint64_t nearest_rank_index(double q, uint64_t n);

/// Count, mean, variance, min and max of a stream of values in O(1) memory.
///
/// Welford's update keeps the variance accurate even for values with a large
/// common offset (1e9 + small), where sum-of-squares formulas cancel; it runs
/// on values shifted by the first one, which keeps the mean's rounding error
/// from growing with the offset too. merge() uses the pairwise combination of
/// Chan, Golub and LeVeque.
class RunningStats {
 public:
  void add(double x);
  uint64_t count() const { return count_; }
  double mean() const { return shift_ + mean_; }
  /// Sample variance (divisor n - 1); 0 for fewer than two values.
  double variance() const;
  double stddev() const;
  /// Exact extremes; 0 when empty.
  double min() const { return count_ == 0 ? 0.0 : min_; }
  double max() const { return count_ == 0 ? 0.0 : max_; }
  /// Sum of all values (mean * count).
  double sum() const { return mean() * static_cast<double>(count_); }
  /// Afterwards this equals the stats of both inputs' values together.
  void merge(const RunningStats& other);

 private:
  uint64_t count_ = 0;
  double shift_ = 0.0;  // the first value; moments are kept relative to it
  double mean_ = 0.0;   // mean of (x - shift_)
  double m2_ = 0.0;     // sum of squared deviations from the running mean
  double min_ = 0.0;
  double max_ = 0.0;
};

/// Quantiles with bounded relative error in memory bounded by the value range.
///
/// Bucket i (i an integer) holds magnitudes in (gamma^(i-1), gamma^i] with
/// gamma = (1 + a) / (1 - a), a = relative_error; its representative value
/// 2 * gamma^i / (gamma + 1) is within relative error a of every magnitude in
/// the bucket. Magnitudes below min_positive share one zero bucket
/// (represented by 0); negative values use mirrored buckets. Counts live in
/// dense arrays indexed by bucket, so memory grows with log(max/min) of the
/// magnitudes seen (about 1400 buckets per six decades at a = 0.005, plus at
/// most a third for growth slack), never
/// with the number of values. The bound holds up to floating-point rounding
/// of the logarithm at bucket edges (a few ulps).
class LogHistogram {
 public:
  /// relative_error in [1e-4, 0.5] (smaller would make the bucket arrays
  /// huge); min_positive finite and > 0. Throws std::invalid_argument otherwise.
  explicit LogHistogram(double relative_error = 0.005, double min_positive = 1e-9);

  void add(double x) { add(x, 1); }
  /// Adds x as if it were added `weight` times (weight 0 does nothing).
  void add(double x, uint64_t weight);
  uint64_t count() const { return count_; }
  /// Nearest-rank quantile (see file comment), clamped to the exact [min, max]
  /// seen and exactly min / max at the extreme ranks; 0 when empty. Relative error <= relative_error() for values whose
  /// magnitude is >= min_positive.
  double quantile(double q) const;
  /// Exact extremes of the values added; 0 when empty.
  double min() const { return count_ == 0 ? 0.0 : min_; }
  double max() const { return count_ == 0 ? 0.0 : max_; }
  /// Adds another histogram's counts; both must have the same relative_error
  /// and min_positive (std::invalid_argument otherwise).
  void merge(const LogHistogram& other);
  /// Non-empty buckets as (representative value, count), ascending by value.
  std::vector<std::pair<double, uint64_t>> buckets() const;
  double relative_error() const { return relative_error_; }
  double min_positive() const { return min_positive_; }
  /// Bucket slots currently allocated (the memory footprint, in counters).
  size_t allocated_buckets() const { return positive_.slots() + negative_.slots(); }

 private:
  // Counts for a contiguous run of bucket indices, grown at either end.
  class DenseCounts {
   public:
    void add(int32_t index, uint64_t weight);
    uint64_t at(int32_t index) const;
    int32_t first_index() const { return offset_; }
    int32_t end_index() const { return offset_ + static_cast<int32_t>(counts_.size()); }
    size_t slots() const { return counts_.size(); }

   private:
    int32_t offset_ = 0;  // bucket index of counts_[0]
    std::vector<uint64_t> counts_;
  };

  int32_t bucket_index(double magnitude) const;
  double representative(int32_t index) const;
  // Bucket value at a 0-based rank in the ascending order of all values.
  double value_at_rank(uint64_t rank) const;

  double relative_error_;
  double min_positive_;
  double gamma_;
  double log_gamma_;
  DenseCounts positive_;
  DenseCounts negative_;  // indexed by the bucket of |x|
  uint64_t zero_count_ = 0;
  uint64_t count_ = 0;
  double min_ = 0.0;
  double max_ = 0.0;
};

/// A model's output channel for one quantity: RunningStats for moments, a
/// LogHistogram for quantiles, and optionally every exact sample.
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
  uint64_t count() const { return stats_.count(); }
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
  void release_samples();

  RunningStats stats_;
  LogHistogram histogram_;
  bool keep_samples_;
  size_t max_samples_;
  std::vector<double> samples_;
};

}  // namespace latsim::des
