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

/// A half-open range [begin, end) of positions in a run order.
struct RunChunk {
  size_t begin = 0, end = 0;
};

/// The run order `point_of_run` (each run's point, in the order the runs
/// start) cut into the pieces a thread takes at a time: consecutive runs of
/// one point, at most max(1, runs / (4 threads)) long, so that a point's
/// replications share a thread's binding and caches while every thread
/// still gets about four pieces of the whole.
std::vector<RunChunk> point_chunks(const std::vector<size_t>& point_of_run, unsigned threads);

}  // namespace latsim::sweep
