// The registry of every pipeline latsim ships (run/src/builtin_pipelines.cpp
// has one line per pipeline).
#pragma once

#include "latsim/pipelines/pipeline.hpp"

namespace latsim::run {

/// The registry with every pipeline latsim ships.
pipelines::PipelineRegistry builtin_pipelines();

}  // namespace latsim::run
