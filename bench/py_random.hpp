// A uniform random stream that reproduces CPython's `random` module bit for
// bit (random.seed(int) then random.random()), so the C++ and Python PHOLD
// programs draw identical numbers. Written from the published MT19937
// algorithm (Matsumoto & Nishimura 1998, reference code mt19937ar.c) and
// CPython's documented use of it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace latsim::bench {

/// MT19937 seeded like CPython's random.seed(n) for a non-negative integer n.
class PyRandom {
 public:
  explicit PyRandom(uint64_t seed) {
    // CPython feeds init_by_array with the 32-bit words of |n|, least
    // significant first; zero still gives one word.
    std::vector<uint32_t> key{static_cast<uint32_t>(seed)};
    if ((seed >> 32) != 0) key.push_back(static_cast<uint32_t>(seed >> 32));
    seed_by_array(key);
  }

  /// CPython's random(): 53 random bits from two 32-bit outputs (27 + 26).
  double random() {
    const uint32_t high27 = next_u32() >> 5;
    const uint32_t low26 = next_u32() >> 6;
    return (static_cast<double>(high27) * 67108864.0 + static_cast<double>(low26)) / 9007199254740992.0;
  }

  uint32_t next_u32() {
    if (pos_ == kStateWords) regenerate();
    uint32_t y = state_[pos_++];
    // Tempering, as specified for MT19937.
    y ^= y >> 11;
    y ^= (y << 7) & 0x9d2c5680u;
    y ^= (y << 15) & 0xefc60000u;
    y ^= y >> 18;
    return y;
  }

 private:
  static constexpr int kStateWords = 624;
  static constexpr int kShift = 397;
  static constexpr uint32_t kMatrixA = 0x9908b0dfu;

  void seed_linear(uint32_t s) {
    state_[0] = s;
    for (int i = 1; i < kStateWords; ++i) {
      const uint32_t prev = state_[i - 1];
      state_[i] = 1812433253u * (prev ^ (prev >> 30)) + static_cast<uint32_t>(i);
    }
    pos_ = kStateWords;
  }

  void seed_by_array(const std::vector<uint32_t>& key) {
    seed_linear(19650218u);
    const int n = kStateWords;
    const int len = static_cast<int>(key.size());
    int i = 1;
    int j = 0;
    for (int rounds = n > len ? n : len; rounds > 0; --rounds) {
      const uint32_t prev = state_[i - 1];
      state_[i] = (state_[i] ^ ((prev ^ (prev >> 30)) * 1664525u)) + key[j] + static_cast<uint32_t>(j);
      if (++i >= n) {
        state_[0] = state_[n - 1];
        i = 1;
      }
      if (++j >= len) j = 0;
    }
    for (int rounds = n - 1; rounds > 0; --rounds) {
      const uint32_t prev = state_[i - 1];
      state_[i] = (state_[i] ^ ((prev ^ (prev >> 30)) * 1566083941u)) - static_cast<uint32_t>(i);
      if (++i >= n) {
        state_[0] = state_[n - 1];
        i = 1;
      }
    }
    state_[0] = 0x80000000u;  // guarantees a non-zero state
  }

  // state[k] for the next block from its old value, its successor and the word kShift ahead.
  static uint32_t twisted(uint32_t current, uint32_t next, uint32_t ahead) {
    const uint32_t y = (current & 0x80000000u) | (next & 0x7fffffffu);
    return ahead ^ (y >> 1) ^ ((y & 1u) != 0 ? kMatrixA : 0u);
  }

  // Produces the next 624 words in place; split in three runs so no index
  // needs a modulo.
  void regenerate() {
    constexpr int kTail = kStateWords - kShift;
    int k = 0;
    for (; k < kTail; ++k) state_[k] = twisted(state_[k], state_[k + 1], state_[k + kShift]);
    for (; k < kStateWords - 1; ++k) state_[k] = twisted(state_[k], state_[k + 1], state_[k - kTail]);
    state_[k] = twisted(state_[k], state_[0], state_[kShift - 1]);
    pos_ = 0;
  }

  std::array<uint32_t, kStateWords> state_{};
  int pos_ = kStateWords;
};

}  // namespace latsim::bench
