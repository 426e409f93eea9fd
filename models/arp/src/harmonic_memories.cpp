#include "latsim/arp/harmonic_memories.hpp"

#include <stdexcept>

namespace latsim::arp {

HarmonicMemories::HarmonicMemories(des::RationalSeconds base_period, int count) : base_(base_period), count_(count) {
  if (count < 1 || count > 30) throw std::invalid_argument("harmonic memories: count must lie in [1, 30]");
  if (base_period.num <= 0 || base_period.den <= 0) {
    throw std::invalid_argument("harmonic memories: the base period must be positive");
  }
}

des::RationalSeconds HarmonicMemories::period(int memory) const {
  if (memory < 0 || memory >= count_) throw std::out_of_range("harmonic memories: no such memory");
  return des::RationalSeconds{base_.num << memory, base_.den};
}

bool HarmonicMemories::has_slot(int memory, int64_t tick) const {
  const int64_t stride = int64_t{1} << memory;
  return tick % stride == 0;
}

int HarmonicMemories::memory_for_validity(double validity_s) const {
  int chosen = 0;
  for (int i = 1; i < count_; ++i) {
    if (period_s(i) <= validity_s) chosen = i;
  }
  return chosen;
}

}  // namespace latsim::arp
