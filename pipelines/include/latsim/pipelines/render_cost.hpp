// How long a generic renderer takes for one frame.
#pragma once

#include "latsim/des/random.hpp"
#include "latsim/des/time.hpp"
#include "latsim/params/shared.hpp"
#include "latsim/scenario/params.hpp"

namespace latsim::pipelines {

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
  /// The cost of drawing the scene's triangles and coverage (none without a
  /// scene) on a width x height display, both eyes per frame in stereo.
  static RenderCost for_scene(const Params& params, const params::SceneParams* scene, int width_px, int height_px,
                              int eyes);

  /// Duration of the next frame; draws from `stream` only when variation is on.
  des::Time frame_time(des::RandomStream& stream) const;
  des::Time nominal_frame_time() const { return nominal_; }
  bool varies() const { return params_.variation != Variation::None && params_.variation_fraction > 0; }

 private:
  Params params_;
  des::Time nominal_;
};

/// Declares the cost terms of a "render" object.
void bind(scenario::Section& s, RenderCost::Params& p);

}  // namespace latsim::pipelines
