// Tests for RandomStream: reproducibility, independence and distribution shapes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "latsim/des/random.hpp"

using latsim::des::fnv1a64;
using latsim::des::mix64;
using latsim::des::RandomStream;

namespace {

constexpr int kDraws = 100'000;

// Pearson correlation of paired uniform draws from two streams.
double correlation(RandomStream a, RandomStream b, int n) {
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (int i = 0; i < n; ++i) {
    const double x = a.uniform01();
    const double y = b.uniform01();
    sa += x;
    sb += y;
    saa += x * x;
    sbb += y * y;
    sab += x * y;
  }
  const double dn = n;
  const double cov = sab / dn - (sa / dn) * (sb / dn);
  const double va = saa / dn - (sa / dn) * (sa / dn);
  const double vb = sbb / dn - (sb / dn) * (sb / dn);
  return cov / std::sqrt(va * vb);
}

// Pearson chi-square statistic of observed counts against equal expectation.
double chi_square_equal(const std::vector<uint64_t>& counts) {
  const double total = std::accumulate(counts.begin(), counts.end(), 0.0);
  const double expected = total / static_cast<double>(counts.size());
  double chi2 = 0;
  for (const uint64_t c : counts) {
    const double d = static_cast<double>(c) - expected;
    chi2 += d * d / expected;
  }
  return chi2;
}

// A loose upper bound for chi-square with `dof` degrees of freedom: about six
// standard deviations above the mean, so a correct generator essentially never
// fails while a biased one (the counts here are large) fails by a wide margin.
double chi_square_bound(double dof) { return dof + 6.0 * std::sqrt(2.0 * dof) + 4.0; }

std::vector<uint64_t> first_values(RandomStream s, int n) {
  std::vector<uint64_t> v;
  for (int i = 0; i < n; ++i) v.push_back(s.next_u64());
  return v;
}

}  // namespace

TEST_CASE("hash and mixer match their published test vectors", "[random]") {
  CHECK(fnv1a64("") == 0xcbf29ce484222325ULL);
  CHECK(fnv1a64("a") == 0xaf63dc4c8601ec8cULL);
  CHECK(fnv1a64("foobar") == 0x85944171f73967e8ULL);
  // First splitmix64 output for seed 1234567.
  CHECK(mix64(1234567ULL + 0x9e3779b97f4a7c15ULL) == 6457827717110365317ULL);
}

TEST_CASE("a stream's first values are pinned", "[random]") {
  // Changing these breaks every recorded result: only on purpose.
  RandomStream s(42, "tracker.noise");
  CHECK(s.key() == 0x97cfb692eb23a98bULL);
  CHECK(RandomStream::key_for(42, "tracker.noise", 0) == s.key());
  CHECK(s.next_u64() == 0x3458b7286c6a43d8ULL);
  CHECK(s.next_u64() == 0x6fcdd005181cc834ULL);
  CHECK(s.next_u64() == 0xb06bcedaac385b74ULL);
  CHECK(s.next_u64() == 0xe42fd641e641a5f3ULL);
}

TEST_CASE("same seed, name and replication give the same sequence", "[random]") {
  RandomStream a(7, "host.jitter", 3);
  RandomStream b(7, "host.jitter", 3);
  for (int i = 0; i < 1000; ++i) {
    REQUIRE(a.next_u64() == b.next_u64());
    REQUIRE(a.normal() == b.normal());
    REQUIRE(a.uniform_int(1000) == b.uniform_int(1000));
  }
}

TEST_CASE("streams do not depend on creation order or on other streams", "[random]") {
  RandomStream first_alone(11, "renderer");
  const auto expected = first_values(first_alone, 8);

  RandomStream other(11, "tracker");
  for (int i = 0; i < 100; ++i) other.next_u64();  // another model draws first
  RandomStream created_later(11, "renderer");
  CHECK(first_values(created_later, 8) == expected);
}

TEST_CASE("different seeds, names or replications give different sequences", "[random]") {
  const auto base = first_values(RandomStream(1, "a", 0), 4);
  CHECK(first_values(RandomStream(2, "a", 0), 4) != base);
  CHECK(first_values(RandomStream(1, "b", 0), 4) != base);
  CHECK(first_values(RandomStream(1, "a", 1), 4) != base);
  // Swapping seed and replication must not give the same key.
  CHECK(RandomStream::key_for(5, "x", 0) != RandomStream::key_for(0, "x", 5));
  CHECK(RandomStream::key_for(0, "", 0) != RandomStream::key_for(0, "", 1));
}

TEST_CASE("related streams are uncorrelated", "[random]") {
  // |r| of independent streams has standard deviation 1/sqrt(n) ~ 0.0032.
  const double bound = 5.0 / std::sqrt(static_cast<double>(kDraws));
  CHECK(std::fabs(correlation(RandomStream(1, "s0"), RandomStream(1, "s1"), kDraws)) < bound);
  CHECK(std::fabs(correlation(RandomStream(1, "s", 0), RandomStream(1, "s", 1), kDraws)) < bound);
  CHECK(std::fabs(correlation(RandomStream(1, "s"), RandomStream(2, "s"), kDraws)) < bound);
  const RandomStream parent(1, "s");
  CHECK(std::fabs(correlation(parent, parent.substream("child"), kDraws)) < bound);
  // A stream against itself must correlate fully, or the helper is broken.
  CHECK(correlation(RandomStream(1, "s"), RandomStream(1, "s"), 1000) == Approx(1.0));
}

TEST_CASE("uniform01 has the mean and variance of the unit interval", "[random]") {
  RandomStream s(3, "uniform");
  double sum = 0, sum_sq = 0;
  for (int i = 0; i < kDraws; ++i) {
    const double u = s.uniform01();
    REQUIRE(u >= 0.0);
    REQUIRE(u < 1.0);
    sum += u;
    sum_sq += u * u;
  }
  const double mean = sum / kDraws;
  const double var = sum_sq / kDraws - mean * mean;
  CHECK(mean == Approx(0.5).margin(0.005));
  CHECK(var == Approx(1.0 / 12.0).margin(0.0015));
}

TEST_CASE("uniform(lo, hi) stays in range and validates its bounds", "[random]") {
  RandomStream s(3, "uniform.range");
  double sum = 0;
  for (int i = 0; i < kDraws; ++i) {
    const double x = s.uniform(-2.0, 6.0);
    REQUIRE(x >= -2.0);
    REQUIRE(x < 6.0);
    sum += x;
  }
  CHECK(sum / kDraws == Approx(2.0).margin(0.05));
  CHECK(s.uniform(1.5, 1.5) == 1.5);
  CHECK_THROWS_AS(s.uniform(2.0, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(s.uniform(0.0, std::nan("")), std::invalid_argument);
}

TEST_CASE("exponential has the requested mean and variance", "[random]") {
  RandomStream s(4, "exponential");
  const double mean_wanted = 2.5;
  double sum = 0, sum_sq = 0;
  for (int i = 0; i < kDraws; ++i) {
    const double x = s.exponential(mean_wanted);
    REQUIRE(x >= 0.0);
    REQUIRE(std::isfinite(x));
    sum += x;
    sum_sq += x * x;
  }
  const double mean = sum / kDraws;
  CHECK(mean == Approx(mean_wanted).margin(0.05));
  CHECK(sum_sq / kDraws - mean * mean == Approx(mean_wanted * mean_wanted).epsilon(0.05));
  CHECK(s.exponential(0.0) == 0.0);
  CHECK_THROWS_AS(s.exponential(-1.0), std::invalid_argument);
}

TEST_CASE("normal has the requested mean, stddev and Gaussian tails", "[random]") {
  RandomStream s(5, "normal");
  const double mu = 3.0, sigma = 2.0;
  double sum = 0, sum_sq = 0;
  int beyond_2sigma = 0, beyond_3sigma = 0;
  for (int i = 0; i < kDraws; ++i) {
    const double x = s.normal(mu, sigma);
    sum += x;
    sum_sq += x * x;
    const double z = std::fabs(x - mu) / sigma;
    beyond_2sigma += z > 2.0;
    beyond_3sigma += z > 3.0;
  }
  const double mean = sum / kDraws;
  CHECK(mean == Approx(mu).margin(0.03));
  CHECK(std::sqrt(sum_sq / kDraws - mean * mean) == Approx(sigma).margin(0.025));
  // P(|Z| > 2) = 0.0455 and P(|Z| > 3) = 0.0027 (4550 and 270 expected).
  CHECK(beyond_2sigma > 4200);
  CHECK(beyond_2sigma < 4900);
  CHECK(beyond_3sigma > 190);
  CHECK(beyond_3sigma < 350);
  CHECK_THROWS_AS(s.normal(0.0, -1.0), std::invalid_argument);
}

TEST_CASE("bernoulli hits p and respects the edge cases", "[random]") {
  RandomStream s(6, "bernoulli");
  int hits = 0;
  for (int i = 0; i < kDraws; ++i) hits += s.bernoulli(0.3);
  CHECK(hits / static_cast<double>(kDraws) == Approx(0.3).margin(0.01));
  for (int i = 0; i < 1000; ++i) {
    REQUIRE_FALSE(s.bernoulli(0.0));
    REQUIRE(s.bernoulli(1.0));
  }
  CHECK_THROWS_AS(s.bernoulli(1.5), std::invalid_argument);
  CHECK_THROWS_AS(s.bernoulli(std::nan("")), std::invalid_argument);
}

TEST_CASE("uniform_int is unbiased for small n (chi-square)", "[random]") {
  RandomStream s(8, "uniform_int");
  for (const uint64_t n : {2ULL, 3ULL, 5ULL, 7ULL, 10ULL, 17ULL}) {
    std::vector<uint64_t> counts(n, 0);
    for (int i = 0; i < 70'000; ++i) {
      const uint64_t k = s.uniform_int(n);
      REQUIRE(k < n);
      ++counts[k];
    }
    INFO("n = " << n);
    CHECK(chi_square_equal(counts) < chi_square_bound(static_cast<double>(n - 1)));
  }
  CHECK(s.uniform_int(1) == 0);
  CHECK_THROWS_AS(s.uniform_int(0), std::invalid_argument);
}

TEST_CASE("uniform_int has no modulo bias for n near 2^64", "[random]") {
  // n = 3 * 2^62: reducing next_u64() modulo n would put half of all results
  // below 2^62 instead of the correct third.
  RandomStream s(9, "uniform_int.large");
  const uint64_t n = 3ULL << 62;
  int low = 0;
  const int draws = 30'000;
  for (int i = 0; i < draws; ++i) {
    const uint64_t k = s.uniform_int(n);
    REQUIRE(k < n);
    low += k < (1ULL << 62);
  }
  CHECK(low / static_cast<double>(draws) == Approx(1.0 / 3.0).margin(0.015));
}

TEST_CASE("shuffle gives a permutation, reproducibly and uniformly", "[random]") {
  std::vector<int> v(1000);
  std::iota(v.begin(), v.end(), 0);
  const auto original = v;
  RandomStream s(10, "shuffle");
  s.shuffle(v);
  CHECK(v != original);
  auto again = original;
  RandomStream t(10, "shuffle");
  t.shuffle(again);
  CHECK(again == v);
  std::sort(v.begin(), v.end());
  CHECK(v == original);

  // All 6 orders of 3 elements equally likely.
  std::vector<uint64_t> counts(6, 0);
  for (int i = 0; i < 60'000; ++i) {
    std::vector<int> p{0, 1, 2};
    s.shuffle(p);
    ++counts[static_cast<size_t>(p[0] * 2 + (p[1] > p[2] ? 1 : 0))];
  }
  CHECK(chi_square_equal(counts) < chi_square_bound(5.0));

  std::vector<int> empty;
  s.shuffle(empty);
  CHECK(empty.empty());
}

TEST_CASE("substreams are deterministic and independent of the parent's draws", "[random]") {
  RandomStream parent(12, "pipeline");
  const auto child_before = first_values(parent.substream("eye.left"), 4);
  for (int i = 0; i < 50; ++i) parent.next_u64();
  CHECK(first_values(parent.substream("eye.left"), 4) == child_before);
  CHECK(first_values(parent.substream("eye.right"), 4) != child_before);
  CHECK(first_values(RandomStream(12, "pipeline"), 4) != child_before);
  // A substream is not the same as a top-level stream of the child's name.
  CHECK(parent.substream("eye.left").key() != RandomStream(12, "eye.left").key());
}
