// The conventional double-buffered pipeline (the worked example in docs/adding-a-pipeline.md).
#pragma once

#include <memory>

#include "latsim/pipelines/pipeline.hpp"

namespace latsim::pipelines {

/// /pipeline: {"type": "double_buffer", "vsync": true, "queued_frames": 0,
/// "render": {"fixed_ms", "per_primitive_us", "per_pixel_ns", "variation", "variation_fraction"}}.
std::unique_ptr<Pipeline> make_double_buffer_pipeline();

}  // namespace latsim::pipelines
