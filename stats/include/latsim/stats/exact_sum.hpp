// Exact, order-independent sums of binary floating-point terms.
//
// A FixedPointSum holds its total as a fixed-point integer in units of
// 2^kMinExponent, spread over 32-bit digits that live in signed 64-bit limbs;
// carries are propagated only every 2^30 additions, so adding a term costs a
// shift and three limb updates. Because nothing is ever rounded, any grouping
// and any order of the same terms gives the same bits: a run of values added
// in closed form equals the same values added one by one.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace latsim::stats {

using u128 = unsigned __int128;

/// An unsigned 256-bit integer (little-endian 64-bit words), for the closed-form
/// sums of runs whose products outgrow 128 bits.
struct U256 {
  std::array<uint64_t, 4> w{};

  static U256 of(u128 v) { return U256{{static_cast<uint64_t>(v), static_cast<uint64_t>(v >> 64), 0, 0}}; }
  /// a * b, exact.
  static U256 product(u128 a, u128 b);
  /// this + o; throws std::overflow_error past 2^256.
  U256 plus(const U256& o) const;
  bool is_zero() const { return (w[0] | w[1] | w[2] | w[3]) == 0; }
};

/// An arbitrary-size unsigned integer in base 2^32 (least significant digit
/// first), used only when a summary is computed, never per sample.
class BigUint {
 public:
  BigUint() = default;
  explicit BigUint(std::vector<uint32_t> digits);
  const std::vector<uint32_t>& digits() const { return d_; }
  bool is_zero() const { return d_.empty(); }
  BigUint times(uint64_t k) const;
  BigUint times(const BigUint& o) const;
  /// this - o; o must not exceed this (std::logic_error otherwise).
  BigUint minus(const BigUint& o) const;
  bool less_than(const BigUint& o) const;
  /// Divides in place by k > 0 and returns the remainder.
  uint64_t divide(uint64_t k);
  /// (negative ? -1 : 1) * this * 2^scale_exponent rounded to the nearest
  /// double (ties to even); `sticky` says that nonzero bits below this value
  /// were cut off (they break ties upwards).
  double to_double(int scale_exponent, bool negative, bool sticky) const;

 private:
  void trim();
  std::vector<uint32_t> d_;
};

/// An exact sum of terms m * 2^e (m an integer, e >= kMinExponent) whose total
/// stays below 2^(kMinExponent + 32 * (kLimbs - 3)).
template <int kMinExponent, int kLimbs>
class FixedPointSum {
 public:
  /// Adds (negative ? -m : m) * 2^exponent.
  void add(uint64_t m, int exponent, bool negative) {
    const int pos = exponent - kMinExponent;
    const int k = pos >> 5;
    if (pos < 0 || k + 2 >= kLimbs) [[unlikely]] throw_out_of_range();
    const u128 v = static_cast<u128>(m) << (pos & 31);  // below 2^95
    const auto d0 = static_cast<int64_t>(static_cast<uint32_t>(v));
    const auto d1 = static_cast<int64_t>(static_cast<uint32_t>(v >> 32));
    const auto d2 = static_cast<int64_t>(static_cast<uint64_t>(v >> 64));
    if (negative) {
      limbs_[k] -= d0;
      limbs_[k + 1] -= d1;
      limbs_[k + 2] -= d2;
    } else {
      limbs_[k] += d0;
      limbs_[k + 1] += d1;
      limbs_[k + 2] += d2;
    }
    // Each addition moves a limb by less than 2^32: 2^30 of them fit in 62 bits.
    if (++pending_ == kNormalizeEvery) [[unlikely]] normalize();
  }
  void add(const U256& m, int exponent, bool negative) {
    for (int i = 0; i < 4; ++i)
      if (m.w[i] != 0) add(m.w[i], exponent + 64 * i, negative);
  }
  /// Adds another sum's total.
  void merge(const FixedPointSum& o) {
    normalize();
    FixedPointSum other = o;
    other.normalize();
    for (int k = 0; k < kLimbs; ++k) limbs_[k] += other.limbs_[k];
    pending_ = 1;
  }
  /// The magnitude of the total in units of 2^kMinExponent, and its sign.
  BigUint magnitude(bool& negative) const {
    FixedPointSum c = *this;
    c.normalize();
    negative = c.limbs_[kLimbs - 1] < 0;
    if (negative) {
      for (auto& l : c.limbs_) l = -l;
      c.normalize();
    }
    std::vector<uint32_t> digits(kLimbs + 1);
    for (int k = 0; k < kLimbs; ++k) digits[k] = static_cast<uint32_t>(c.limbs_[k]);
    digits[kLimbs] = static_cast<uint32_t>(static_cast<uint64_t>(c.limbs_[kLimbs - 1]) >> 32);
    return BigUint(std::move(digits));
  }
  static constexpr int min_exponent() { return kMinExponent; }

 private:
  static constexpr uint32_t kNormalizeEvery = uint32_t{1} << 30;

  // Carries every limb but the top one into [0, 2^32); the top one keeps the sign.
  void normalize() {
    for (int k = 0; k + 1 < kLimbs; ++k) {
      const int64_t carry = limbs_[k] >> 32;  // floor division by 2^32
      limbs_[k] -= carry * (int64_t{1} << 32);
      limbs_[k + 1] += carry;
    }
    pending_ = 0;
  }
  [[noreturn]] static void throw_out_of_range() {
    throw std::overflow_error("FixedPointSum: a term lies outside the exactly summable range");
  }

  std::array<int64_t, kLimbs> limbs_{};
  uint32_t pending_ = 0;
};

}  // namespace latsim::stats
