// Named, reproducible random streams for the models.
//
// Every model draws from its own RandomStream, keyed by (run seed,
// replication, stream name). The key is a hash, so a stream's sequence does
// not depend on which other streams exist or in what order they were made:
// adding a model to a scenario leaves the numbers of every other model alone.
//
// Generator: xoshiro256** (Blackman & Vigna), state filled by splitmix64 from
// the 64-bit key. Names are hashed with FNV-1a 64 and then mixed with the
// splitmix64 finaliser. Everything is integer arithmetic or IEEE-exact
// operations except exponential() and normal(), which call std::log (and
// std::log1p); these are the only places results could differ between C
// libraries. No std::*_distribution is used, because their algorithms differ
// between standard libraries.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

namespace latsim::des {

/// FNV-1a 64-bit hash of a byte string (offset 0xcbf29ce484222325, prime
/// 0x100000001b3); fixed here so stream keys never change between builds.
uint64_t fnv1a64(std::string_view bytes);

/// The splitmix64 finaliser: a bijective 64-bit mixer with full avalanche.
uint64_t mix64(uint64_t x);

/// One independent, reproducible stream of pseudo-random numbers.
class RandomStream {
 public:
  /// Key = hash of (run_seed, replication, name); see key_for().
  RandomStream(uint64_t run_seed, std::string_view name, uint64_t replication = 0);

  /// The key a stream with these inputs is seeded from (documented, stable).
  static uint64_t key_for(uint64_t run_seed, std::string_view name, uint64_t replication);

  /// The next raw 64-bit output of xoshiro256**.
  uint64_t next_u64();
  /// Uniform on [0, 1) with 53 random bits (the top bits of next_u64()).
  double uniform01();
  /// Uniform on [lo, hi); throws std::invalid_argument unless lo <= hi, both finite.
  double uniform(double lo, double hi);
  /// Uniform integer in [0, n), exactly unbiased (Lemire's multiply-and-reject);
  /// throws std::invalid_argument for n == 0.
  uint64_t uniform_int(uint64_t n);
  /// Exponential with the given mean (>= 0) by inversion: -mean * log(1 - U).
  double exponential(double mean);
  /// Normal by the Marsaglia polar method; the second variate of each pair is
  /// cached and returned by the next call, so draws come in pairs.
  double normal(double mean = 0.0, double stddev = 1.0);
  /// True with probability p in [0, 1] (one uniform01() draw).
  bool bernoulli(double p);

  /// Fisher-Yates shuffle driven by uniform_int(), so it is the same everywhere
  /// (std::shuffle's algorithm is implementation-defined).
  template <class T>
  void shuffle(std::vector<T>& v) {
    for (size_t i = v.size(); i > 1; --i) {
      const auto j = static_cast<size_t>(uniform_int(static_cast<uint64_t>(i)));
      using std::swap;
      swap(v[i - 1], v[j]);
    }
  }

  /// A child stream derived from this stream's key and the child's name only,
  /// not from how many numbers this stream has drawn, so it is deterministic
  /// wherever it is created.
  RandomStream substream(std::string_view name) const;

  /// The 64-bit key this stream was seeded from.
  uint64_t key() const { return key_; }

 private:
  explicit RandomStream(uint64_t key);
  void seed_from_key();

  uint64_t key_ = 0;
  uint64_t state_[4] = {0, 0, 0, 0};
  // The polar method yields two normals per accepted pair; keeping the spare
  // halves the cost and keeps the sequence a pure function of the draws made.
  double spare_normal_ = 0.0;
  bool has_spare_normal_ = false;
};

}  // namespace latsim::des
