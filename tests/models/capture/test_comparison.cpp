// The two-sample Kolmogorov-Smirnov distance and the percentiles of latsim
// compare against small examples worked by hand.
#include <catch2/catch.hpp>

#include "latsim/capture/comparison.hpp"

using latsim::capture::ks_distance;
using latsim::capture::percentile_sorted;
using latsim::capture::sample_stats;

TEST_CASE("comparison: KS distances worked by hand") {
  // a = {1, 2, 3}, b = {2, 4}. F_a at 1, 2, 3, 4: 1/3, 2/3, 1, 1; F_b: 0,
  // 1/2, 1/2, 1. |F_a - F_b|: 1/3, 1/6, 1/2, 0: D = 1/2.
  CHECK(*ks_distance({1, 2, 3}, {2, 4}) == Approx(0.5).margin(1e-15));
  CHECK(*ks_distance({5, 1, 3}, {3, 1, 5}) == 0.0);  // a sample and itself reordered
  CHECK(*ks_distance({1, 2}, {3, 4}) == 1.0);        // disjoint
  // Ties across samples: a = {1, 1, 2}, b = {1, 2, 2}: at 1: 2/3 - 1/3; at 2: 0. D = 1/3.
  CHECK(*ks_distance({1, 1, 2}, {1, 2, 2}) == Approx(1.0 / 3.0).margin(1e-15));
  // Shares of 0/1 values: the distance is the difference of the shares of ones.
  CHECK(*ks_distance({0, 0, 0, 1}, {0, 1}) == Approx(0.25).margin(1e-15));
  CHECK_FALSE(ks_distance({}, {1}));
}

TEST_CASE("comparison: percentiles linear between order statistics, and the mean") {
  // p50 of 1..5 is 3; p99: rank 0.99 * 4 = 3.96, 4 + 0.96 * (5 - 4) = 4.96.
  CHECK(percentile_sorted({1, 2, 3, 4, 5}, 50) == 3.0);
  CHECK(percentile_sorted({1, 2, 3, 4, 5}, 99) == Approx(4.96).margin(1e-12));
  CHECK(percentile_sorted({7}, 99) == 7.0);
  const auto s = sample_stats({5, 4, 3, 2, 1});
  CHECK(s.count == 5);
  CHECK(*s.mean == 3.0);
  CHECK(*s.p50 == 3.0);
  CHECK(*s.min == 1.0);
  CHECK(*s.max == 5.0);
  CHECK_FALSE(sample_stats({}).mean);
}
