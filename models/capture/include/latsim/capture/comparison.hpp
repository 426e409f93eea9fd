// Two samples of one quantity side by side: their summary statistics and the
// two-sample Kolmogorov-Smirnov distance (latsim compare).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace latsim::capture {

/// Count, mean and percentiles of a sample (none of them for an empty one).
struct SampleStats {
  int64_t count = 0;
  std::optional<double> mean, p50, p99, min, max;
};

/// The statistics of `values`; percentiles linear between order statistics
/// (rank q/100 × (n - 1) from 0, numpy's default).
SampleStats sample_stats(std::vector<double> values);

/// The q-th percentile of sorted values, linear between order statistics.
double percentile_sorted(const std::vector<double>& sorted, double q);

/// sup |F_a(x) - F_b(x)| over the pooled sample points, F the empirical
/// (right-continuous) distribution functions: 0 for the same distribution
/// of values, 1 for disjoint ones. None when either sample is empty.
std::optional<double> ks_distance(std::vector<double> a, std::vector<double> b);

}  // namespace latsim::capture
