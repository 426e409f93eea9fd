#include "latsim/pipelines/render_cost.hpp"

#include <algorithm>

namespace latsim::pipelines {

RenderCost::RenderCost(Params params, int64_t primitives, int64_t covered_pixels) : params_(params) {
  const double ms = params_.fixed_ms + params_.per_primitive_us * 1e-3 * static_cast<double>(primitives) +
                    params_.per_pixel_ns * 1e-6 * static_cast<double>(covered_pixels);
  nominal_ = des::Time::from_ms(ms);
}

RenderCost RenderCost::for_scene(const Params& params, const params::SceneParams* scene, int width_px, int height_px,
                                 int eyes) {
  const int64_t triangles = scene ? scene->triangles : 0;
  const double coverage = scene ? scene->coverage : 1.0;
  // Both eyes are rendered per frame in stereo.
  const int64_t pixels = static_cast<int64_t>(coverage * width_px * height_px) * eyes;
  return RenderCost(params, triangles * eyes, pixels);
}

void bind(scenario::Section& s, RenderCost::Params& p) {
  s.doc("Frame time = fixed + per primitive × triangles + per covered pixel × covered pixels (both eyes in stereo), "
        "from /scene's `triangles` and `coverage`, optionally varied per frame.");
  s.number("fixed_ms", p.fixed_ms, {.unit = "ms", .min = 0.0, .doc = "fixed time per frame"});
  s.number("per_primitive_us", p.per_primitive_us, {.unit = "us", .min = 0.0, .doc = "time per triangle"});
  s.number("per_pixel_ns", p.per_pixel_ns, {.unit = "ns", .min = 0.0, .doc = "time per covered pixel"});
  s.choice("variation", p.variation,
           {{"none", RenderCost::Variation::None},
            {"uniform", RenderCost::Variation::Uniform},
            {"normal", RenderCost::Variation::Normal}},
           {.doc = "random factor per frame"});
  s.number("variation_fraction", p.variation_fraction,
           {.min = 0.0, .max = 1.0, .doc = "uniform: ±fraction; normal: standard deviation as a fraction"});
}

des::Time RenderCost::frame_time(des::RandomStream& stream) const {
  if (!varies()) return nominal_;
  double factor = 1.0;
  if (params_.variation == Variation::Uniform)
    factor = 1.0 + stream.uniform(-params_.variation_fraction, params_.variation_fraction);
  else
    factor = 1.0 + stream.normal(0.0, params_.variation_fraction);
  factor = std::max(factor, 0.0);
  return des::Time::from_seconds(nominal_.to_seconds() * factor);
}

}  // namespace latsim::pipelines
