// The keys of a generic renderer's cost ("render" and stage "cost" objects).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/sections/shared.hpp"
#include "latsim/renderer/render_cost.hpp"
#include "latsim/scenario/section.hpp"

namespace latsim::sections {

/// Declares the cost terms of a "render" object.
void bind(scenario::Section& s, renderer::RenderCost::Params& p);

/// Declares the optional "trace" object of a cost (a capture column played
/// back); reads and checks the capture with the scenario, so that a bad
/// capture is an error at its key in validate as in run.
void bind_trace(scenario::Section& s, renderer::RenderCost::Params& p);

/// summary.json's entry for a measured cost after its run: the capture, the
/// rows read, kept and skipped by reason, and how the replay went (null for
/// a modelled cost).
nlohmann::json trace_summary(const renderer::RenderCost& cost);

/// Warnings on a measured cost from a PresentMon capture replayed on a
/// display of `refresh_hz` (capture::presentmon_warnings: uncapped, composed,
/// another refresh rate, CPU busy read as work); none for other costs.
std::vector<std::string> trace_warnings(const renderer::RenderCost& cost, double refresh_hz);

/// The warning of a run ended at `now` because a measured cost with
/// at_end "stop" played its last value.
std::string trace_ran_out(const renderer::RenderCost& cost, des::Time now);

/// The cost of drawing the scene's triangles and coverage (none and full
/// coverage without a scene) on a width x height display, both eyes per
/// frame in stereo.
renderer::RenderCost render_cost_for_scene(const renderer::RenderCost::Params& params, const SceneParams* scene,
                                           int width_px, int height_px, int eyes);

}  // namespace latsim::sections
