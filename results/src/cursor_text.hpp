// Text written at a cursor into a buffer sized beforehand for the longest
// possible entry: no bounds checks, no string growth. The timeline and the
// PresentMon log write their rows with these, exact and the same bytes on
// every platform.
#pragma once

#include <charconv>
#include <cstdint>
#include <cstring>
#include <string_view>

namespace latsim::results::cursor {

/// 10^n, for the fixed-point widths below.
constexpr int64_t pow10(int n) { return n == 0 ? 1 : 10 * pow10(n - 1); }

/// Copies `s` and moves the cursor past it.
inline void put(char*& p, std::string_view s) {
  std::memcpy(p, s.data(), s.size());
  p += s.size();
}

/// A whole number in decimal (at most 20 characters).
inline void put_int(char*& p, int64_t v) { p = std::to_chars(p, p + 24, v).ptr; }

/// Exactly `digits` decimal digits of v (leading zeros kept), two at a time.
inline void put_digits(char*& p, uint64_t v, int digits) {
  static constexpr char kPairs[] =
      "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
      "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
      "8081828384858687888990919293949596979899";
  char* const end = p + digits;
  char* q = end;
  for (; digits >= 2; digits -= 2, v /= 100) {
    q -= 2;
    std::memcpy(q, kPairs + 2 * (v % 100), 2);
  }
  if (digits == 1) *--q = static_cast<char>('0' + v % 10);
  p = end;
}

/// ticks / PerUnit as a decimal with Digits digits after the point, from
/// integers: exact, no rounding.
template <int64_t PerUnit, int Digits>
void put_fixed(char*& p, int64_t ticks) {
  static_assert(PerUnit == pow10(Digits), "a remainder of ticks / PerUnit must fill exactly Digits digits");
  const uint64_t mag = ticks < 0 ? uint64_t{0} - static_cast<uint64_t>(ticks) : static_cast<uint64_t>(ticks);
  if (ticks < 0) *p++ = '-';
  p = std::to_chars(p, p + 24, mag / static_cast<uint64_t>(PerUnit)).ptr;
  *p++ = '.';
  put_digits(p, mag % static_cast<uint64_t>(PerUnit), Digits);
}

}  // namespace latsim::results::cursor
