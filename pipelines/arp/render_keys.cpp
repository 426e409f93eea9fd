#include "arp/render_keys.hpp"

#include <string>

namespace latsim::pipelines {

void bind_render_costs(scenario::Section& s, arp::MemoryRenderCost& cost, int& renderers,
                       std::string_view per_unit_key, std::string_view unit_doc) {
  s.duration("render_fixed_ms", cost.fixed, {.unit = "ms", .doc = "fixed time per display-memory update"});
  const std::string per_unit_doc = "time per " + std::string(unit_doc);
  s.duration(per_unit_key, cost.per_segment, {.unit = "us", .doc = per_unit_doc});
  s.number("render_per_pixel_ns", cost.per_pixel_ns,
           {.unit = "ns", .min = 0.0, .max = 1e6,
            .doc = "time per cube-memory pixel the drawn geometry covers (occluded or not), the fill cost"});
  s.integer("renderers", renderers,
            {.min = 1.0, .max = 64.0, .doc = "renderers drawing display-memory updates, fastest memory first"});
}

}  // namespace latsim::pipelines
