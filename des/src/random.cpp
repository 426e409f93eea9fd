#include "latsim/des/random.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace latsim::des {

namespace {

constexpr uint64_t kGolden = 0x9e3779b97f4a7c15ULL;
// Domain tags keep the three inputs of a key (and substream derivation) from
// colliding with each other, e.g. seed 5 + replication 0 vs seed 0 + replication 5.
constexpr uint64_t kSeedTag = 0x5eed5eed5eed5eedULL;
constexpr uint64_t kReplicationTag = 0x7265706c69636174ULL;  // "replicat"
constexpr uint64_t kSubstreamTag = 0x7375627374726561ULL;    // "substrea"

uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

uint64_t fnv1a64(std::string_view bytes) {
  uint64_t h = 0xcbf29ce484222325ULL;
  for (const char c : bytes) {
    h ^= static_cast<uint64_t>(static_cast<unsigned char>(c));
    h *= 0x100000001b3ULL;
  }
  return h;
}

uint64_t mix64(uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

uint64_t RandomStream::key_for(uint64_t run_seed, std::string_view name, uint64_t replication) {
  // Chained mixing: each input passes through a full-avalanche mixer before it
  // meets the next, so nearby seeds or replications give unrelated keys.
  uint64_t k = mix64(run_seed ^ kSeedTag);
  k = mix64(k ^ mix64(replication + kReplicationTag));
  k = mix64(k ^ mix64(fnv1a64(name)));
  return k;
}

RandomStream::RandomStream(uint64_t run_seed, std::string_view name, uint64_t replication)
    : key_(key_for(run_seed, name, replication)) {
  seed_from_key();
}

RandomStream::RandomStream(uint64_t key) : key_(key) { seed_from_key(); }

void RandomStream::seed_from_key() {
  // splitmix64 sequence from the key, as the xoshiro authors recommend; it
  // never yields four zero words, the one state xoshiro cannot leave.
  uint64_t s = key_;
  for (auto& word : state_) {
    s += kGolden;
    word = mix64(s);
  }
  has_spare_normal_ = false;
  spare_normal_ = 0.0;
}

uint64_t RandomStream::next_u64() {
  const uint64_t result = rotl(state_[1] * 5, 7) * 9;
  const uint64_t t = state_[1] << 17;
  state_[2] ^= state_[0];
  state_[3] ^= state_[1];
  state_[1] ^= state_[2];
  state_[0] ^= state_[3];
  state_[2] ^= t;
  state_[3] = rotl(state_[3], 45);
  return result;
}

double RandomStream::uniform01() {
  // Top 53 bits are the best of xoshiro256**'s output; scaling by 2^-53 is exact.
  return static_cast<double>(next_u64() >> 11) * 0x1.0p-53;
}

double RandomStream::uniform(double lo, double hi) {
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo <= hi)) {
    throw std::invalid_argument("RandomStream::uniform: need finite lo <= hi, got [" +
                                std::to_string(lo) + ", " + std::to_string(hi) + ")");
  }
  const double x = lo + (hi - lo) * uniform01();
  // Rounding can land exactly on hi when hi - lo is large relative to lo.
  return x < hi ? x : lo;
}

uint64_t RandomStream::uniform_int(uint64_t n) {
  if (n == 0) throw std::invalid_argument("RandomStream::uniform_int: n must be positive");
  // Lemire (2019): the high word of x*n is uniform on [0, n) once the low
  // words that would over-represent some values are rejected.
  unsigned __int128 m = static_cast<unsigned __int128>(next_u64()) * n;
  auto low = static_cast<uint64_t>(m);
  if (low < n) {
    const uint64_t threshold = (0 - n) % n;  // 2^64 mod n
    while (low < threshold) {
      m = static_cast<unsigned __int128>(next_u64()) * n;
      low = static_cast<uint64_t>(m);
    }
  }
  return static_cast<uint64_t>(m >> 64);
}

double RandomStream::exponential(double mean) {
  if (!(std::isfinite(mean) && mean >= 0.0)) {
    throw std::invalid_argument("RandomStream::exponential: mean must be finite and >= 0, got " +
                                std::to_string(mean));
  }
  // 1 - U lies in (0, 1], so the logarithm is always finite.
  return -mean * std::log1p(-uniform01());
}

double RandomStream::normal(double mean, double stddev) {
  if (!(std::isfinite(mean) && std::isfinite(stddev) && stddev >= 0.0)) {
    throw std::invalid_argument("RandomStream::normal: need finite mean and stddev >= 0");
  }
  if (has_spare_normal_) {
    has_spare_normal_ = false;
    return mean + stddev * spare_normal_;
  }
  double u = 0.0;
  double v = 0.0;
  double s = 0.0;
  do {
    u = 2.0 * uniform01() - 1.0;
    v = 2.0 * uniform01() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * std::log(s) / s);
  spare_normal_ = v * factor;
  has_spare_normal_ = true;
  return mean + stddev * (u * factor);
}

bool RandomStream::bernoulli(double p) {
  if (!(p >= 0.0 && p <= 1.0)) {
    throw std::invalid_argument("RandomStream::bernoulli: p must be in [0, 1], got " +
                                std::to_string(p));
  }
  return uniform01() < p;
}

RandomStream RandomStream::substream(std::string_view name) const {
  return RandomStream(mix64(mix64(key_ ^ kSubstreamTag) ^ mix64(fnv1a64(name))));
}

}  // namespace latsim::des
