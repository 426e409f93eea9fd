// /pipeline/pacing/steamvr and /pipeline/pacing/oculus as the scenario writes them.
#pragma once

#include "frame_stages/pacing.hpp"
#include "latsim/scenario/section.hpp"

namespace latsim::pipelines::frame_stages {

/// Declares (and reads) the runtimes' keys of /pipeline/pacing.
void bind_runtime_pacing(scenario::Section& s, PacingSpec& p);

}  // namespace latsim::pipelines::frame_stages
