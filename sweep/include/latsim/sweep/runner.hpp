// One sweep on this machine's threads, as `latsim sweep` (without --mpi) and
// latsim.sweep in Python run it: check every point of the runs chosen, run
// the unfinished ones longest expected first, and write the tables.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "latsim/sweep/common.hpp"
#include "latsim/sweep/plan.hpp"
#include "latsim/sweep/progress_line.hpp"

namespace latsim::sweep {

/// How a sweep went.
struct SweepOutcome {
  /// The first bad point, as its error line shows it: nothing was run or written.
  std::optional<std::string> problem;
  size_t selected = 0;     ///< runs asked for (the shard's, or all)
  SweepTally tally;
  size_t temporaries = 0;  ///< temporary files of interrupted attempts removed
  bool stopped = false;    ///< a stop signal came: the tables were not written
  bool tables_written = false;
  size_t tabled = 0;       ///< runs in the tables
  std::optional<std::string> tables_problem;  ///< why the tables could not be written
  PhaseTimes phases;
};

/// Runs the runs of `plan` at the plan positions `selected` into
/// request.out_dir on request.jobs threads (each run at most once, a finished
/// run never again), and writes the tables from every finished run of the
/// plan when `write_tables` is set and the runs went through. `progress`
/// (may be null) is advanced per run. Throws only when the sweep directory
/// cannot be made.
SweepOutcome run_sweep(const SweepPlan& plan, const SweepRequest& request, const std::vector<size_t>& selected,
                       bool write_tables, ProgressLine* progress);

}  // namespace latsim::sweep
