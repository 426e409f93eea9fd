// What a run is expected to cost, so that the longest runs can start first.
#pragma once

#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

namespace latsim::app {

/// A run's expected cost from its resolved scenario (every default filled
/// in): simulated seconds times the display's events per simulated second at
/// its scanout fidelity, that is fields (field), active lines per field
/// (line) or active pixels per field over pixel_stride (pixel); two displays
/// when stereo. Event counts grow exactly so with
/// fidelity (BENCHMARKS.md, "Sweeps and fidelity"), and wall time with events.
/// A scenario without a display costs its simulated seconds.
double expected_cost(const nlohmann::json& resolved);

/// The order to start runs in: `indices` by expected cost, largest first, ties
/// (and so every run of a plan whose runs all cost the same) in the order given.
std::vector<size_t> longest_first(std::vector<size_t> indices, const std::vector<double>& cost_of_index);

}  // namespace latsim::app
