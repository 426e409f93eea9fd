// A stage's cost changing over a run: steps at given frames and random
// spikes, for workloads that pacing must follow (docs/pacing.md).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "latsim/des/random.hpp"
#include "latsim/des/time.hpp"
#include "latsim/renderer/render_cost.hpp"

namespace latsim::pipelines::frame_stages {

/// Steps replace the cost model from a job on; a spike adds to one job's cost.
struct CostShape {
  std::vector<std::pair<int64_t, des::Time>> steps;  ///< (first job, duration), by first job
  double spike_probability = 0.0;                    ///< per job
  des::Time spike;                                   ///< added to a spiking job

  bool empty() const { return steps.empty() && spike_probability <= 0.0; }
};

/// Job j's duration: the last step at or before j (else the cost model),
/// plus a spike with its probability (drawn only when spikes are on).
inline des::Time shaped_cost(renderer::RenderCost& cost, const CostShape& shape, int64_t job,
                             des::RandomStream& stream) {
  des::Time t;
  bool stepped = false;
  for (const auto& [from, duration] : shape.steps)
    if (from <= job) {
      t = duration;
      stepped = true;
    }
  if (!stepped) t = cost.frame_time(stream);
  if (shape.spike_probability > 0.0 && stream.bernoulli(shape.spike_probability)) t += shape.spike;
  return t;
}

}  // namespace latsim::pipelines::frame_stages
