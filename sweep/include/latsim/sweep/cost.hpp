// What a run is expected to cost, so that the longest runs can start first.
#pragma once

#include <cstddef>
#include <vector>

#include "latsim/sections/shared.hpp"
#include "latsim/scenario/config.hpp"

namespace latsim::sweep {

/// A run's expected cost from its shared parameters as the run reads them:
/// simulated seconds times the display's events per simulated second at its
/// scanout fidelity, that is fields (field), active lines per field (line)
/// or active pixels per field over pixel_stride (pixel); two displays when
/// stereo. Event counts grow exactly so with fidelity (BENCHMARKS.md,
/// "Sweeps and fidelity"), and wall time with events.
double expected_cost(const sections::SharedParams& p);

/// The same for a scenario: its shared sections read through their
/// declarations (every default as a run takes it). Throws
/// scenario::ScenarioError on bad input, as a run would.
double expected_cost(const scenario::ScenarioDocument& doc);

/// The order to start runs in: `indices` by expected cost, largest first, ties
/// (and so every run of a plan whose runs all cost the same) in the order given.
std::vector<size_t> longest_first(std::vector<size_t> indices, const std::vector<double>& cost_of_index);

}  // namespace latsim::sweep
