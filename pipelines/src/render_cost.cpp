#include "latsim/pipelines/render_cost.hpp"

#include <algorithm>

namespace latsim::pipelines {

RenderCost::RenderCost(Params params, int64_t primitives, int64_t covered_pixels) : params_(params) {
  const double ms = params_.fixed_ms + params_.per_primitive_us * 1e-3 * static_cast<double>(primitives) +
                    params_.per_pixel_ns * 1e-6 * static_cast<double>(covered_pixels);
  nominal_ = des::Time::from_ms(ms);
}

RenderCost RenderCost::from_config(const scenario::ConfigNode& render, const scenario::ConfigNode* scene,
                                   int width_px, int height_px, int eyes) {
  Params p;
  p.fixed_ms = render.non_negative("fixed_ms", 0.0);
  p.per_primitive_us = render.non_negative("per_primitive_us", 0.0);
  p.per_pixel_ns = render.non_negative("per_pixel_ns", 0.0);
  const std::string v = render.choice("variation", "none", {"none", "uniform", "normal"});
  p.variation = v == "none" ? Variation::None : v == "uniform" ? Variation::Uniform : Variation::Normal;
  p.variation_fraction = render.number_in("variation_fraction", 0.0, 0.0, 1.0);
  int64_t triangles = 0;
  double coverage = 1.0;
  if (scene) {
    triangles = scene->integer("triangles", 0, 0, int64_t{1} << 40);
    coverage = scene->number_in("coverage", 1.0, 0.0, 1.0);
  }
  // Both eyes are rendered per frame in stereo.
  const int64_t pixels = static_cast<int64_t>(coverage * width_px * height_px) * eyes;
  return RenderCost(p, triangles * eyes, pixels);
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
