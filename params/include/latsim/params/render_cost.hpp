// The keys of a generic renderer's cost ("render" and stage "cost" objects).
#pragma once

#include "latsim/params/shared.hpp"
#include "latsim/renderer/render_cost.hpp"
#include "latsim/scenario/params.hpp"

namespace latsim::params {

/// Declares the cost terms of a "render" object.
void bind(scenario::Section& s, renderer::RenderCost::Params& p);

/// The cost of drawing the scene's triangles and coverage (none and full
/// coverage without a scene) on a width x height display, both eyes per
/// frame in stereo.
renderer::RenderCost render_cost_for_scene(const renderer::RenderCost::Params& params, const SceneParams* scene,
                                           int width_px, int height_px, int eyes);

}  // namespace latsim::params
