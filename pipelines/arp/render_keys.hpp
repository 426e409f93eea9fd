// The renderer keys the priority and region priority pipelines share.
#pragma once

#include <string_view>

#include "latsim/arp/memory_render_cost.hpp"
#include "latsim/scenario/section.hpp"

namespace latsim::pipelines {

/// Declares render_fixed_ms, the per-unit time `per_unit_key` (us per
/// `unit_doc`), render_per_pixel_ns and renderers.
void bind_render_costs(scenario::Section& s, arp::MemoryRenderCost& cost, int& renderers,
                       std::string_view per_unit_key, std::string_view unit_doc);

}  // namespace latsim::pipelines
