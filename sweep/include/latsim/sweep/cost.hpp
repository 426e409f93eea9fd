// What a run is expected to cost, so that the longest runs can start first.
#pragma once

#include <cstddef>
#include <vector>

#include "latsim/run/event_budget.hpp"

namespace latsim::sweep {

/// A run's expected cost: the events of its own estimate
/// (docs/event-budget.md), the one estimate its build makes for the event
/// budget (run::PreparedRun::estimate()), events and steps of work together.
double expected_cost(const run::EventEstimate& estimate);

/// The order to start runs in: `indices` by expected cost, largest first, ties
/// (and so every run of a plan whose runs all cost the same) in the order given.
std::vector<size_t> longest_first(std::vector<size_t> indices, const std::vector<double>& cost_of_index);

}  // namespace latsim::sweep
