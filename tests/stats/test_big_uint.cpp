// BigUint's product and division, checked by identities that use neither
// shortcut they take (zero rows skipped, 64-bit division for small divisors):
// residues modulo primes above 2^32 (the 128-bit division) and q k + r = n.
#include <catch2/catch.hpp>

#include <cstdint>
#include <random>
#include <vector>

#include "latsim/stats/exact_sum.hpp"

namespace {

using latsim::stats::BigUint;

// Digits as a sum's magnitude has them: runs of zeros below and between a few nonzero ones.
BigUint random_big(std::mt19937_64& rng, size_t digits) {
  std::vector<uint32_t> d(digits, 0);
  for (size_t i = 0; i < digits; ++i)
    if (rng() % 3 == 0 || i + 1 == digits) d[i] = static_cast<uint32_t>(rng() | 1);
  return BigUint(std::move(d));
}

// n mod p for p above 2^32: the division by a divisor that needs 128 bits.
uint64_t residue(BigUint n, uint64_t p) { return n.divide(p); }

uint64_t mul_mod(uint64_t a, uint64_t b, uint64_t p) {
  return static_cast<uint64_t>(static_cast<unsigned __int128>(a) * b % p);
}

}  // namespace

TEST_CASE("a product with zero digits has the residues of its factors' product", "[stats][exact]") {
  // Primes above 2^32 (2^61 - 1, a Mersenne prime; 2^32 + 15).
  const uint64_t primes[] = {(uint64_t{1} << 61) - 1, (uint64_t{1} << 32) + 15};
  std::mt19937_64 rng(44);
  for (int trial = 0; trial < 200; ++trial) {
    const BigUint a = random_big(rng, 1 + rng() % 70), b = random_big(rng, 1 + rng() % 70);
    const BigUint ab = a.times(b);
    for (uint64_t p : primes) CHECK(residue(ab, p) == mul_mod(residue(a, p), residue(b, p), p));
    // A one-digit factor: the same as the product by a machine word.
    const BigUint one_digit(std::vector<uint32_t>{b.digits().front()});
    CHECK(a.times(one_digit).digits() == a.times(uint64_t{b.digits().front()}).digits());
  }
  CHECK(BigUint().times(BigUint(std::vector<uint32_t>{0, 0, 5})).is_zero());
}

TEST_CASE("a division by a small divisor leaves q and r with q k + r = n and r < k", "[stats][exact]") {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 500; ++trial) {
    const BigUint n = random_big(rng, 1 + rng() % 70);
    // Counts: 1, 2, the usual and the largest that fits 32 bits.
    const uint64_t divisors[] = {1, 2, 1 + rng() % 100000, UINT32_MAX, static_cast<uint64_t>(UINT32_MAX) + 1};
    for (uint64_t k : divisors) {
      BigUint q = n;
      const uint64_t r = q.divide(k);
      CHECK(r < k);
      const BigUint rest = n.minus(q.times(k));
      CHECK(rest.digits() == BigUint(std::vector<uint32_t>{static_cast<uint32_t>(r), static_cast<uint32_t>(r >> 32)}).digits());
    }
  }
}
