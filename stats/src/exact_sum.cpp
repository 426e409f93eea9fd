#include "latsim/stats/exact_sum.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace latsim::stats {

U256 U256::product(u128 a, u128 b) {
  // Schoolbook on 64-bit halves; each partial product fits in 128 bits.
  const uint64_t a0 = static_cast<uint64_t>(a), a1 = static_cast<uint64_t>(a >> 64);
  const uint64_t b0 = static_cast<uint64_t>(b), b1 = static_cast<uint64_t>(b >> 64);
  U256 r;
  const u128 p00 = static_cast<u128>(a0) * b0;
  const u128 p01 = static_cast<u128>(a0) * b1;
  const u128 p10 = static_cast<u128>(a1) * b0;
  const u128 p11 = static_cast<u128>(a1) * b1;
  r.w[0] = static_cast<uint64_t>(p00);
  u128 mid = (p00 >> 64) + static_cast<uint64_t>(p01) + static_cast<uint64_t>(p10);
  r.w[1] = static_cast<uint64_t>(mid);
  u128 high = (mid >> 64) + (p01 >> 64) + (p10 >> 64) + static_cast<uint64_t>(p11);
  r.w[2] = static_cast<uint64_t>(high);
  r.w[3] = static_cast<uint64_t>((high >> 64) + static_cast<uint64_t>(p11 >> 64));
  return r;
}

U256 U256::plus(const U256& o) const {
  U256 r;
  u128 carry = 0;
  for (int i = 0; i < 4; ++i) {
    const u128 s = static_cast<u128>(w[i]) + o.w[i] + carry;
    r.w[i] = static_cast<uint64_t>(s);
    carry = s >> 64;
  }
  if (carry != 0) throw std::overflow_error("U256: sum exceeds 256 bits");
  return r;
}

BigUint::BigUint(std::vector<uint32_t> digits) : d_(std::move(digits)) { trim(); }

void BigUint::trim() {
  while (!d_.empty() && d_.back() == 0) d_.pop_back();
}

BigUint BigUint::times(uint64_t k) const {
  std::vector<uint32_t> out(d_.size() + 2, 0);
  u128 carry = 0;
  for (size_t i = 0; i < d_.size(); ++i) {
    const u128 p = static_cast<u128>(d_[i]) * k + carry;
    out[i] = static_cast<uint32_t>(p);
    carry = p >> 32;
  }
  out[d_.size()] = static_cast<uint32_t>(carry);
  out[d_.size() + 1] = static_cast<uint32_t>(carry >> 32);
  return BigUint(std::move(out));
}

BigUint BigUint::times(const BigUint& o) const {
  std::vector<uint32_t> out(d_.size() + o.d_.size() + 1, 0);
  for (size_t i = 0; i < d_.size(); ++i) {
    // A sum's low digits are mostly zero (its unit is 2^-1074): a zero row adds nothing.
    if (d_[i] == 0) continue;
    uint64_t carry = 0;
    for (size_t j = 0; j < o.d_.size(); ++j) {
      // (2^32-1)^2 + 2 (2^32-1) = 2^64 - 1: never overflows.
      const uint64_t t = static_cast<uint64_t>(d_[i]) * o.d_[j] + out[i + j] + carry;
      out[i + j] = static_cast<uint32_t>(t);
      carry = t >> 32;
    }
    for (size_t k = i + o.d_.size(); carry != 0; ++k) {
      const uint64_t t = static_cast<uint64_t>(out[k]) + carry;
      out[k] = static_cast<uint32_t>(t);
      carry = t >> 32;
    }
  }
  return BigUint(std::move(out));
}

bool BigUint::less_than(const BigUint& o) const {
  if (d_.size() != o.d_.size()) return d_.size() < o.d_.size();
  for (size_t i = d_.size(); i-- > 0;)
    if (d_[i] != o.d_[i]) return d_[i] < o.d_[i];
  return false;
}

BigUint BigUint::minus(const BigUint& o) const {
  if (less_than(o)) throw std::logic_error("BigUint::minus: the result would be negative");
  std::vector<uint32_t> out(d_);
  int64_t borrow = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    int64_t t = static_cast<int64_t>(out[i]) - borrow - (i < o.d_.size() ? static_cast<int64_t>(o.d_[i]) : 0);
    borrow = t < 0 ? 1 : 0;
    if (t < 0) t += int64_t{1} << 32;
    out[i] = static_cast<uint32_t>(t);
  }
  return BigUint(std::move(out));
}

uint64_t BigUint::divide(uint64_t k) {
  if (k == 0) throw std::domain_error("BigUint::divide by zero");
  if (k <= UINT32_MAX) {
    // The same digits by 64-bit division (a count, by far the usual divisor):
    // rem < k < 2^32, so rem * 2^32 + digit fits in 64 bits.
    uint64_t rem = 0;
    for (size_t i = d_.size(); i-- > 0;) {
      const uint64_t cur = (rem << 32) | d_[i];
      d_[i] = static_cast<uint32_t>(cur / k);
      rem = cur % k;
    }
    trim();
    return rem;
  }
  u128 rem = 0;
  for (size_t i = d_.size(); i-- > 0;) {
    const u128 cur = (rem << 32) | d_[i];  // rem < k < 2^64: fits in 96 bits
    d_[i] = static_cast<uint32_t>(cur / k);
    rem = cur % k;
  }
  trim();
  return static_cast<uint64_t>(rem);
}

double BigUint::to_double(int scale_exponent, bool negative, bool sticky) const {
  if (d_.empty()) return negative ? -0.0 : 0.0;
  // The top 96 bits, normalised so that the leading one is bit 127.
  const size_t h = d_.size() - 1;
  u128 top = static_cast<u128>(d_[h]) << 64;
  if (h >= 1) top |= static_cast<u128>(d_[h - 1]) << 32;
  if (h >= 2) top |= d_[h - 2];
  for (size_t i = 0; i + 2 < h; ++i) sticky = sticky || d_[i] != 0;
  const int lz = (top >> 64) != 0 ? __builtin_clzll(static_cast<uint64_t>(top >> 64))
                                  : 64 + __builtin_clzll(static_cast<uint64_t>(top));
  top <<= lz;
  uint64_t bits64 = static_cast<uint64_t>(top >> 64);
  sticky = sticky || static_cast<uint64_t>(top) != 0;
  // value = bits64 * 2^e64 with the leading one at bit 63.
  int e64 = scale_exponent + 32 * (static_cast<int>(h) - 2) - lz + 64;
  // Round 64 bits to 53, ties to even (sticky bits count as above the tie).
  uint64_t mant = bits64 >> 11;
  const uint64_t rest = bits64 & 0x7FF;
  if (rest > 0x400 || (rest == 0x400 && (sticky || (mant & 1) != 0))) ++mant;
  if (mant == (uint64_t{1} << 53)) {
    mant >>= 1;
    ++e64;
  }
  const double v = std::ldexp(static_cast<double>(mant), e64 + 11);
  return negative ? -v : v;
}

}  // namespace latsim::stats
