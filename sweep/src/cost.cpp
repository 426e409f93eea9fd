#include "latsim/sweep/cost.hpp"

#include <algorithm>

namespace latsim::sweep {

double expected_cost(const run::EventEstimate& estimate) { return estimate.events; }

std::vector<size_t> longest_first(std::vector<size_t> indices, const std::vector<double>& cost_of_index) {
  std::stable_sort(indices.begin(), indices.end(),
                   [&](size_t a, size_t b) { return cost_of_index[a] > cost_of_index[b]; });
  return indices;
}

}  // namespace latsim::sweep
