// Building the scene the address recalculation pipelines draw from a
// scenario's /scene object.
#pragma once

#include "latsim/renderer/scene.hpp"
#include "latsim/scenario/config.hpp"

namespace latsim::arp {

/// Reads {"type": "gallery" | "room" | "test_pattern" | "obj", ...}: the gallery
/// takes size_x_m, size_z_m, height_m, partition_count, frames_per_wall and
/// tile_m; "obj" takes "path".
renderer::Scene scene_from_config(const scenario::ConfigNode& node);

}  // namespace latsim::arp
