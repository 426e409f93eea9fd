// The address recalculation pipelines: plain ARP ("arp"), priority rendering
// ("priority") and region priority rendering ("region_priority").
#pragma once

#include <memory>

#include "latsim/pipelines/pipeline.hpp"

namespace latsim::pipelines {

/// Adds "arp", "priority" and "region_priority" to a registry.
void register_arp_pipelines(PipelineRegistry& registry);

std::unique_ptr<Pipeline> make_arp_pipeline();
std::unique_ptr<Pipeline> make_priority_pipeline();
std::unique_ptr<Pipeline> make_region_priority_pipeline();

}  // namespace latsim::pipelines
