// Display memories updated at harmonic rates (60, 30, 15, 7.5 Hz ...) and the
// choice of memory for an object's validity period.
#pragma once

#include <cstdint>
#include <vector>

#include "latsim/des/time.hpp"

namespace latsim::arp {

/// A set of display memories: memory i may update every 2^i-th tick of the
/// fastest rate, so its period is exactly 2^i times the base period.
class HarmonicMemories {
 public:
  /// `base_period` is the fastest memory's update period; `count` in [1, 30].
  HarmonicMemories(des::RationalSeconds base_period, int count);

  int count() const { return count_; }
  /// Exact update period of memory i.
  des::RationalSeconds period(int memory) const;
  double period_s(int memory) const { return period(memory).to_seconds(); }
  double rate_hz(int memory) const { return 1.0 / period_s(memory); }
  /// Memory i has an update slot at base tick k when k is a multiple of 2^i.
  bool has_slot(int memory, int64_t tick) const;
  /// The slowest memory whose period does not exceed the validity period, so
  /// the object is redrawn before its image becomes invalid; the fastest when
  /// even that is too slow, the slowest for an infinite period.
  int memory_for_validity(double validity_s) const;

 private:
  des::RationalSeconds base_;
  int count_;
};

}  // namespace latsim::arp
