#include "latsim/sections/render_cost.hpp"

namespace latsim::sections {

void bind(scenario::Section& s, renderer::RenderCost::Params& p) {
  s.doc("Frame time = fixed + per primitive × triangles + per covered pixel × covered pixels (both eyes in stereo), "
        "from /scene's `triangles` and `coverage`, optionally varied per frame.");
  s.number("fixed_ms", p.fixed_ms, {.unit = "ms", .min = 0.0, .doc = "fixed time per frame"});
  s.number("per_primitive_us", p.per_primitive_us, {.unit = "us", .min = 0.0, .doc = "time per triangle"});
  s.number("per_pixel_ns", p.per_pixel_ns, {.unit = "ns", .min = 0.0, .doc = "time per covered pixel"});
  s.choice("variation", p.variation,
           {{"none", renderer::RenderCost::Variation::None},
            {"uniform", renderer::RenderCost::Variation::Uniform},
            {"normal", renderer::RenderCost::Variation::Normal}},
           {.doc = "random factor per frame"});
  s.number("variation_fraction", p.variation_fraction,
           {.min = 0.0, .max = 1.0, .doc = "uniform: ±fraction; normal: standard deviation as a fraction"});
  s.number("variation_correlation_frames", p.variation_correlation_frames,
           {.min = 0.0,
            .doc = "normal: frames over which a frame's factor still correlates with the next ones (falling to 1/e); "
                   "0: each frame drawn on its own"});
  s.check("variation_correlation_frames",
          p.variation_correlation_frames <= 0.0 || p.variation == renderer::RenderCost::Variation::Normal,
          "only a normal variation is correlated from frame to frame");
  bind_trace(s, p);
}

renderer::RenderCost render_cost_for_scene(const renderer::RenderCost::Params& params, const SceneParams* scene,
                                           int width_px, int height_px, int eyes) {
  return renderer::RenderCost::for_scene(params, scene ? scene->triangles : 0, scene ? scene->coverage : 1.0, width_px,
                                         height_px, eyes);
}

}  // namespace latsim::sections
