#include "latsim/sweep/cost.hpp"

#include <algorithm>

namespace latsim::sweep {

double expected_cost(const run::EventEstimate& estimate) { return estimate.events; }

std::vector<size_t> longest_first(std::vector<size_t> indices, const std::vector<double>& cost_of_index) {
  std::stable_sort(indices.begin(), indices.end(),
                   [&](size_t a, size_t b) { return cost_of_index[a] > cost_of_index[b]; });
  return indices;
}

std::vector<RunChunk> point_chunks(const std::vector<size_t>& point_of_run, unsigned threads) {
  const size_t longest = std::max<size_t>(1, point_of_run.size() / (4 * static_cast<size_t>(std::max(1u, threads))));
  std::vector<RunChunk> chunks;
  for (size_t i = 0; i < point_of_run.size(); ++i) {
    const bool same_point = !chunks.empty() && point_of_run[chunks.back().begin] == point_of_run[i];
    if (same_point && chunks.back().end - chunks.back().begin < longest) ++chunks.back().end;
    else chunks.push_back({i, i + 1});
  }
  return chunks;
}

}  // namespace latsim::sweep
