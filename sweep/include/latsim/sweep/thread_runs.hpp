// The one sweep runner on this machine's threads, for `latsim sweep` (without
// --mpi) and the Python module's sweep alike.
#pragma once

#include <atomic>
#include <cstddef>
#include <vector>

#include "latsim/sweep/common.hpp"
#include "latsim/sweep/keep.hpp"
#include "latsim/sweep/plan.hpp"

namespace latsim::sweep {

/// Runs the unfinished runs among `selected` (plan indices) on `jobs`
/// threads, longest expected first (`cost_of_run`, from check_points), each
/// keeping its traces as `keep` says. Once `stop` is set (when given) or the
/// sweep directory cannot take results, no further run starts. Shows a
/// progress line on a terminal. Returns how the runs went, in plan order.
SweepTally run_on_threads(const SweepPlan& plan, const std::vector<size_t>& selected,
                          const std::vector<double>& cost_of_run, SweepWorkspace& work, const KeepPolicy& keep,
                          unsigned jobs, const std::atomic<bool>* stop);

}  // namespace latsim::sweep
