// Tests for RunningStats, LogHistogram and Distribution against exact references.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "latsim/des/random.hpp"
#include "latsim/stats/stats.hpp"

using latsim::stats::Distribution;
using latsim::stats::LogHistogram;
using latsim::stats::nearest_rank_index;
using latsim::des::RandomStream;
using latsim::stats::RunningStats;

namespace {

struct TwoPass {
  double mean = 0;
  double variance = 0;
};

// The textbook two-pass formulas, the reference for the streaming ones.
TwoPass two_pass(const std::vector<double>& xs) {
  TwoPass r;
  r.mean = std::accumulate(xs.begin(), xs.end(), 0.0) / static_cast<double>(xs.size());
  double ss = 0;
  for (const double x : xs) ss += (x - r.mean) * (x - r.mean);
  r.variance = ss / static_cast<double>(xs.size() - 1);
  return r;
}

double exact_quantile(std::vector<double> sorted_values, double q) {
  return sorted_values[nearest_rank_index(q, sorted_values.size())];
}

std::vector<double> probe_quantiles() {
  return {0.0, 0.001, 0.01, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 0.999, 1.0};
}

// Checks every probe quantile of `h` against the exact sorted quantile.
void check_relative_error(const LogHistogram& h, std::vector<double> values) {
  std::sort(values.begin(), values.end());
  // The bound is exact up to rounding of the logarithm at bucket edges.
  const double bound = h.relative_error() * (1.0 + 1e-9);
  for (const double q : probe_quantiles()) {
    const double exact = exact_quantile(values, q);
    const double estimate = h.quantile(q);
    INFO("q = " << q << ", exact = " << exact << ", estimate = " << estimate);
    if (std::fabs(exact) >= h.min_positive()) {
      CHECK(std::fabs(estimate - exact) <= bound * std::fabs(exact));
    }
  }
}

}  // namespace

TEST_CASE("nearest_rank_index follows the nearest-rank definition", "[stats]") {
  CHECK(nearest_rank_index(0.0, 10) == 0);
  CHECK(nearest_rank_index(0.1, 10) == 0);
  CHECK(nearest_rank_index(0.11, 10) == 1);
  CHECK(nearest_rank_index(0.5, 10) == 4);
  CHECK(nearest_rank_index(0.91, 10) == 9);
  CHECK(nearest_rank_index(1.0, 10) == 9);
  CHECK(nearest_rank_index(0.5, 1) == 0);
  CHECK_THROWS_AS(nearest_rank_index(-0.1, 10), std::invalid_argument);
  CHECK_THROWS_AS(nearest_rank_index(1.1, 10), std::invalid_argument);
  CHECK_THROWS_AS(nearest_rank_index(0.5, 0), std::invalid_argument);
}

TEST_CASE("RunningStats matches two-pass formulas", "[stats]") {
  RandomStream rng(1, "stats.two_pass");
  std::vector<double> xs;
  RunningStats s;
  for (int i = 0; i < 10'000; ++i) {
    xs.push_back(rng.normal(5.0, 2.0));
    s.add(xs.back());
  }
  const TwoPass ref = two_pass(xs);
  CHECK(s.count() == xs.size());
  CHECK(s.mean() == Approx(ref.mean).epsilon(1e-12));
  CHECK(s.variance() == Approx(ref.variance).epsilon(1e-12));
  CHECK(s.stddev() == Approx(std::sqrt(ref.variance)).epsilon(1e-12));
  CHECK(s.min() == *std::min_element(xs.begin(), xs.end()));
  CHECK(s.max() == *std::max_element(xs.begin(), xs.end()));
  CHECK(s.sum() == Approx(ref.mean * static_cast<double>(xs.size())).epsilon(1e-12));
}

TEST_CASE("RunningStats survives a large common offset", "[stats]") {
  // Sum-of-squares formulas lose every digit here: x^2 ~ 1e18 while the
  // variance is 30.
  RunningStats small;
  for (const double x : {4.0, 7.0, 13.0, 16.0}) small.add(1e9 + x);
  CHECK(small.mean() == 1e9 + 10.0);
  CHECK(small.variance() == Approx(30.0).epsilon(1e-9));

  RandomStream rng(2, "stats.offset");
  std::vector<double> shifted;
  RunningStats s;
  for (int i = 0; i < 100'000; ++i) {
    const double x = 1e9 + rng.uniform01();
    s.add(x);
    shifted.push_back(x - 1e9);  // exact: x and 1e9 are within a factor of two
  }
  const TwoPass ref = two_pass(shifted);
  // 1e9 has an ulp of 1.2e-7: the mean must be right to about that.
  CHECK(s.mean() - 1e9 == Approx(ref.mean).margin(3e-7));
  CHECK(s.variance() == Approx(ref.variance).epsilon(1e-6));
}

TEST_CASE("RunningStats empty and single-value cases are NaN-free", "[stats]") {
  RunningStats s;
  CHECK(s.count() == 0);
  CHECK(s.mean() == 0.0);
  CHECK(s.variance() == 0.0);
  CHECK(s.stddev() == 0.0);
  CHECK(s.min() == 0.0);
  CHECK(s.max() == 0.0);
  s.add(-3.5);
  CHECK(s.mean() == -3.5);
  CHECK(s.variance() == 0.0);
  CHECK(s.min() == -3.5);
  CHECK(s.max() == -3.5);
}

TEST_CASE("RunningStats merge equals adding everything to one", "[stats]") {
  RandomStream rng(3, "stats.merge");
  RunningStats all, a, b, empty;
  for (int i = 0; i < 5000; ++i) {
    const double x = rng.exponential(3.0) + (i < 1000 ? 100.0 : 0.0);
    all.add(x);
    (i < 1000 ? a : b).add(x);  // unequal halves with different means
  }
  RunningStats merged = a;
  merged.merge(b);
  CHECK(merged.count() == all.count());
  CHECK(merged.mean() == Approx(all.mean()).epsilon(1e-12));
  CHECK(merged.variance() == Approx(all.variance()).epsilon(1e-12));
  CHECK(merged.min() == all.min());
  CHECK(merged.max() == all.max());

  RunningStats into_empty = empty;
  into_empty.merge(a);
  CHECK(into_empty.mean() == a.mean());
  CHECK(into_empty.count() == a.count());
  RunningStats with_empty = a;
  with_empty.merge(empty);
  CHECK(with_empty.variance() == a.variance());
}

TEST_CASE("non-finite samples are rejected loudly", "[stats]") {
  RunningStats s;
  s.add(1.0);
  CHECK_THROWS_AS(s.add(std::nan("")), std::invalid_argument);
  CHECK_THROWS_AS(s.add(INFINITY), std::invalid_argument);
  CHECK(s.count() == 1);
  CHECK(s.mean() == 1.0);
  LogHistogram h;
  CHECK_THROWS_AS(h.add(std::nan("")), std::invalid_argument);
  CHECK(h.count() == 0);
  Distribution d;
  CHECK_THROWS_AS(d.add(-INFINITY), std::invalid_argument);
  CHECK(d.count() == 0);
  CHECK(d.histogram().count() == 0);
}

TEST_CASE("LogHistogram quantiles stay within the relative error bound", "[stats]") {
  for (const double a : {0.01, 0.005, 0.001}) {
    INFO("relative_error = " << a);
    RandomStream rng(4, "stats.quantiles");
    LogHistogram lognormal(a), uniform(a), exponential(a), normal(a);
    std::vector<double> v_lognormal, v_uniform, v_exponential, v_normal;
    for (int i = 0; i < 100'000; ++i) {
      v_lognormal.push_back(std::exp(rng.normal(2.0, 1.0)));
      v_uniform.push_back(rng.uniform(0.5, 100.0));
      v_exponential.push_back(rng.exponential(10.0));
      v_normal.push_back(rng.normal(0.0, 1.0));  // crosses zero: mirrored buckets
      lognormal.add(v_lognormal.back());
      uniform.add(v_uniform.back());
      exponential.add(v_exponential.back());
      normal.add(v_normal.back());
    }
    check_relative_error(lognormal, v_lognormal);
    check_relative_error(uniform, v_uniform);
    check_relative_error(exponential, v_exponential);
    check_relative_error(normal, v_normal);
  }
}

TEST_CASE("LogHistogram memory is bounded by the value range, not the count", "[stats]") {
  LogHistogram h(0.005);
  RandomStream rng(5, "stats.memory");
  const double log_lo = std::log(1e-3), log_hi = std::log(1e3);
  for (int i = 0; i < 10'000'000; ++i) h.add(std::exp(rng.uniform(log_lo, log_hi)));
  CHECK(h.count() == 10'000'000);
  // S = 100 buckets per binade (1/201 < 0.005 <= 1/199); six decades are
  // log2(1e6) = 19.93 binades, so at most 1994 buckets plus one partial at each end.
  CHECK(h.buckets_per_binade() == 100);
  CHECK(h.buckets().size() <= 1996);
  CHECK(h.allocated_buckets() <= 1996 * 4 / 3 + 2);
}

TEST_CASE("LogHistogram handles zero, tiny and negative values", "[stats]") {
  LogHistogram h(0.01, 1e-6);
  for (const double x : {-5.0, -0.5, 0.0, 1e-12, -1e-12, 0.5, 5.0}) h.add(x);
  const auto b = h.buckets();
  REQUIRE(b.size() == 5);
  CHECK(b[0].first == Approx(-5.0).epsilon(0.01));
  CHECK(b[1].first == Approx(-0.5).epsilon(0.01));
  CHECK(b[2].first == 0.0);
  CHECK(b[2].second == 3);  // 0 and both tiny values share the zero bucket
  CHECK(b[3].first == Approx(0.5).epsilon(0.01));
  CHECK(b[4].first == Approx(5.0).epsilon(0.01));
  for (size_t i = 1; i < b.size(); ++i) CHECK(b[i - 1].first < b[i].first);
  // Extremes are exact because quantiles are clamped to the tracked min/max.
  CHECK(h.quantile(0.0) == -5.0);
  CHECK(h.quantile(1.0) == 5.0);
  CHECK(h.quantile(0.5) == 0.0);
  CHECK(h.min() == -5.0);
  CHECK(h.max() == 5.0);
}

TEST_CASE("LogHistogram weights, merge and validation", "[stats]") {
  LogHistogram weighted, repeated;
  weighted.add(2.0, 3);
  weighted.add(7.0, 0);  // weight 0 is a no-op, extremes included
  for (int i = 0; i < 3; ++i) repeated.add(2.0);
  CHECK(weighted.count() == 3);
  CHECK(weighted.buckets() == repeated.buckets());
  CHECK(weighted.max() == 2.0);

  RandomStream rng(6, "stats.hist_merge");
  LogHistogram all, a, b;
  for (int i = 0; i < 20'000; ++i) {
    const double x = rng.normal(0.0, 100.0);
    all.add(x);
    (i % 3 == 0 ? a : b).add(x);
  }
  a.merge(b);
  CHECK(a.count() == all.count());
  CHECK(a.buckets() == all.buckets());
  for (const double q : probe_quantiles()) CHECK(a.quantile(q) == all.quantile(q));
  LogHistogram empty;
  empty.merge(all);
  CHECK(empty.buckets() == all.buckets());
  CHECK(empty.min() == all.min());

  LogHistogram coarse(0.01);
  CHECK_THROWS_AS(coarse.merge(all), std::invalid_argument);
  CHECK_THROWS_AS(LogHistogram(0.0), std::invalid_argument);
  CHECK_THROWS_AS(LogHistogram(0.9), std::invalid_argument);
  CHECK_THROWS_AS(LogHistogram(0.01, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(all.quantile(1.5), std::invalid_argument);

  std::uint64_t total = 0;
  for (const auto& [value, c] : all.buckets()) total += c;
  CHECK(total == all.count());
  CHECK(LogHistogram().quantile(0.5) == 0.0);
}

TEST_CASE("Distribution summary of empty and one-value inputs", "[stats]") {
  const Distribution empty;
  const auto e = empty.summary();
  CHECK(e.count == 0);
  for (const double v : {e.mean, e.stddev, e.min, e.p50, e.p90, e.p99, e.p999, e.max}) {
    CHECK(v == 0.0);
  }
  CHECK(empty.quantile(0.5) == 0.0);
  CHECK(empty.plot_histogram().empty());

  for (const bool keep : {false, true}) {
    Distribution one(0.005, keep);
    one.add(16.7);
    const auto s = one.summary();
    CHECK(s.count == 1);
    CHECK(s.stddev == 0.0);
    for (const double v : {s.mean, s.min, s.p50, s.p90, s.p99, s.p999, s.max}) CHECK(v == 16.7);
    const auto bins = one.plot_histogram(10);
    REQUIRE(bins.size() == 1);
    CHECK(bins[0] == std::pair<double, std::uint64_t>(16.7, 1));
  }
}

TEST_CASE("Distribution keeps exact samples when asked", "[stats]") {
  Distribution d(0.01, true);
  RandomStream rng(7, "stats.exact");
  std::vector<double> xs;
  for (int i = 0; i < 5001; ++i) {
    xs.push_back(rng.exponential(5.0));
    d.add(xs.back());
  }
  CHECK(d.keeps_samples());
  CHECK(d.samples() == xs);  // in insertion order
  std::vector<double> sorted = xs;
  std::sort(sorted.begin(), sorted.end());
  for (const double q : probe_quantiles()) CHECK(d.quantile(q) == exact_quantile(sorted, q));
  const auto s = d.summary();
  CHECK(s.p50 == exact_quantile(sorted, 0.5));
  CHECK(s.p90 == exact_quantile(sorted, 0.9));
  CHECK(s.p99 == exact_quantile(sorted, 0.99));
  CHECK(s.p999 == exact_quantile(sorted, 0.999));
  CHECK(s.min == sorted.front());
  CHECK(s.max == sorted.back());
  CHECK(s.mean == Approx(two_pass(xs).mean).epsilon(1e-12));
}

TEST_CASE("Distribution releases samples past max_samples and falls back", "[stats]") {
  Distribution d(0.005, true, 100);
  std::vector<double> xs;
  for (int i = 1; i <= 100; ++i) {
    xs.push_back(i * 0.37);
    d.add(xs.back());
  }
  CHECK(d.keeps_samples());
  xs.push_back(1000.0);
  d.add(xs.back());
  CHECK_FALSE(d.keeps_samples());
  CHECK(d.samples().empty());
  CHECK(d.count() == 101);
  check_relative_error(d.histogram(), xs);
  CHECK(d.quantile(1.0) == 1000.0);
}

TEST_CASE("Distribution merge combines moments, histogram and samples", "[stats]") {
  Distribution a(0.005, true), b(0.005, true), all(0.005, true);
  for (int i = 0; i < 300; ++i) {
    const double x = std::sin(i) * 10.0;
    (i < 100 ? a : b).add(x);
    all.add(x);
  }
  a.merge(b);
  CHECK(a.keeps_samples());
  CHECK(a.samples() == all.samples());
  CHECK(a.stats().mean() == Approx(all.stats().mean()).epsilon(1e-12));
  CHECK(a.histogram().buckets() == all.histogram().buckets());

  Distribution not_kept(0.005, false);
  not_kept.add(1.0);
  a.merge(not_kept);
  CHECK_FALSE(a.keeps_samples());
  CHECK(a.count() == 301);
}

TEST_CASE("plot_histogram bins span min..max and their counts sum to count", "[stats]") {
  Distribution exact(0.005, true);
  for (int i = 0; i < 100; ++i) exact.add(i);
  const auto bins = exact.plot_histogram(10);
  REQUIRE(bins.size() == 10);
  for (size_t i = 0; i < bins.size(); ++i) {
    CHECK(bins[i].first == Approx(i * 9.9));
    CHECK(bins[i].second == 10);
  }

  Distribution approx(0.005, false);
  RandomStream rng(8, "stats.plot");
  for (int i = 0; i < 50'000; ++i) approx.add(std::exp(rng.normal(1.0, 0.5)));
  for (const int n_bins : {1, 7, 50, 200}) {
    const auto h = approx.plot_histogram(n_bins);
    REQUIRE(h.size() == static_cast<size_t>(n_bins));
    std::uint64_t total = 0;
    for (const auto& [edge, c] : h) total += c;
    CHECK(total == approx.count());
    CHECK(h.front().first == approx.stats().min());
  }
  // A lognormal's mode lies left of centre: the busiest bin is in the left half.
  const auto h = approx.plot_histogram(20);
  const auto busiest = std::max_element(h.begin(), h.end(), [](const auto& x, const auto& y) {
    return x.second < y.second;
  });
  CHECK(busiest - h.begin() < 10);
  CHECK_THROWS_AS(approx.plot_histogram(0), std::invalid_argument);
}
