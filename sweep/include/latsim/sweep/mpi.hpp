// latsim sweep --mpi: one sweep over the ranks of an MPI job.
#pragma once

#include "latsim/sweep/common.hpp"

namespace latsim::sweep {

/// Under mpirun: rank 0 reads and checks the plan, then hands runs out one at
/// a time (each rank holding at most two), longest expected first; every rank
/// runs what it is handed, with `request.jobs` threads (rank 0 too: its
/// dispatcher mostly sleeps), through the same claims as any other sweep, and
/// rank 0 writes the tables at the end. Returns rank 0's exit code on rank 0
/// and 0 on the others. Without MPI support compiled in, says so and returns 2.
int sweep_mpi(const SweepRequest& request);

}  // namespace latsim::sweep
