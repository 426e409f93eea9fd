// The exit codes of latsim's commands, shared by everything that ends a
// process on latsim's behalf (the command line, an MPI sweep's ranks).
#pragma once

namespace latsim::run {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;   ///< the run itself failed (a model error)
inline constexpr int kExitBadInput = 2;  ///< bad scenario or command line: nothing was written

}  // namespace latsim::run
