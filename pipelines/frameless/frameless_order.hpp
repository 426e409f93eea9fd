// Frameless rendering beside double buffering at the same pixel budget
// (Bishop et al.'s comparison): each pixel is computed from the newest pose
// and shown at the next refresh, in a randomised order without replacement.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "latsim/des/random.hpp"
#include "latsim/pipelines/pipeline.hpp"

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

/// /pipeline: {"type": "frameless",
///   "strategy": "frameless" | "double_buffer",
///   "pixels_per_s": N  or  "full_images_per_s": 5 (x width x height x eyes),
///   "chunk_pixels": 2048, "sample_pixels": 1024, "registration_depth_m": 2,
///   "fallback": {"kind": "none" | "low_resolution" | "double_buffer",
///                "trigger_deg": 20, "trigger_m": 0.5, "block_px": 4}}.
/// See docs/frames.md for what each figure means.
std::unique_ptr<Pipeline> make_frameless_pipeline();

}  // namespace latsim::pipelines
