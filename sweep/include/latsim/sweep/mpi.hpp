// latsim sweep --mpi: one sweep over the ranks of an MPI job.
#pragma once

#include <functional>

#include "latsim/sweep/common.hpp"

namespace latsim::sweep {

/// Under mpirun: rank 0 reads and checks the plan, then hands runs out one at
/// a time (each rank holding at most two), longest expected first; every rank
/// runs what it is handed, with `request.jobs` threads (rank 0 too: its
/// dispatcher mostly sleeps), through the same claims as any other sweep, and
/// rank 0 writes the tables at the end. Returns rank 0's exit code on rank 0
/// and 0 on the others. Without MPI support compiled in, says so and returns 2.
///
/// Once *request.stop is set (mpiexec passes a SIGTERM or SIGINT on to every
/// rank), no run is handed out or started, the runs under way end at their
/// next event, the ranks drop what they hold and every rank returns
/// stopped(rank == 0) without writing the tables: rank 0's says so in one
/// line, the others' say nothing.
int sweep_mpi(const SweepRequest& request, const std::function<int(bool lead)>& stopped);

}  // namespace latsim::sweep
