// /pipeline/pacing and a stage's /cost_shape as the scenario writes them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "frame_stages/spec.hpp"
#include "latsim/scenario/section.hpp"

namespace latsim::pipelines::frame_stages {

/// /pipeline/pacing as read: the spec, with the span stages still by name.
struct PacingKeys {
  PacingSpec spec;
  std::string draw_stage, gpu_stage;
};

void bind_pacing(scenario::Section& s, PacingKeys& p);
/// In the pipeline's section `s`: resolves the stage names and checks what a policy needs (a warp for the compositor's and half rate).
void resolve_pacing(scenario::Section& s, PacingKeys& p, const std::vector<StageSpec>& stages, bool has_warp);
void bind_cost_shape(scenario::Section& s, CostShape& shape);

}  // namespace latsim::pipelines::frame_stages
