// How long a generic renderer takes for one frame.
#pragma once

#include <cstdint>

#include "latsim/des/random.hpp"
#include "latsim/des/time.hpp"

namespace latsim::renderer {

/// Frame time = fixed + per primitive x primitives + per covered pixel x
/// covered pixels, optionally varied by a random factor per frame.
class RenderCost {
 public:
  enum class Variation { None, Uniform, Normal };
  struct Params {
    double fixed_ms = 0.0;
    double per_primitive_us = 0.0;
    double per_pixel_ns = 0.0;
    Variation variation = Variation::None;
    double variation_fraction = 0.0;  ///< uniform: +-fraction; normal: stddev as a fraction
  };

  RenderCost() = default;
  RenderCost(Params params, int64_t primitives, int64_t covered_pixels);
  /// The cost of drawing `triangles` triangles covering a `coverage` fraction
  /// of a width x height display, for each of `eyes` eyes per frame (both
  /// eyes are rendered per frame in stereo).
  static RenderCost for_scene(const Params& params, int64_t triangles, double coverage, int width_px, int height_px,
                              int eyes);

  /// Duration of the next frame; draws from `stream` only when variation is on.
  des::Time frame_time(des::RandomStream& stream) const;
  des::Time nominal_frame_time() const { return nominal_; }
  bool varies() const { return params_.variation != Variation::None && params_.variation_fraction > 0; }

 private:
  Params params_;
  des::Time nominal_;
};

}  // namespace latsim::renderer
