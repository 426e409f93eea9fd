// The randomised order in which frameless rendering updates pixels.
#pragma once

#include <cstdint>
#include <vector>

#include "latsim/des/random.hpp"

namespace latsim::pipelines {

/// The order frameless rendering updates pixels in: one random permutation of
/// all pixels, drawn once and repeated, so that every pixel is updated exactly
/// once in each cycle of pixel_count() updates.
class FramelessOrder {
 public:
  /// Shuffles 0 .. pixel_count-1 with `stream` (Fisher-Yates, the same on every platform).
  FramelessOrder(int32_t pixel_count, des::RandomStream stream);
  int32_t pixel_count() const { return static_cast<int32_t>(table_.size()); }
  /// The pixel written by update number `update` (counted from 0).
  int32_t pixel_of(int64_t update) const {
    return table_[static_cast<size_t>(update % static_cast<int64_t>(table_.size()))];
  }

 private:
  std::vector<int32_t> table_;
};

}  // namespace latsim::pipelines
