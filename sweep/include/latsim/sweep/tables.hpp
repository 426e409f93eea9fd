// The tables of a sweep directory (results.csv, results.sqlite), and what is
// missing from them.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "latsim/sweep/claims.hpp"
#include "latsim/sweep/plan.hpp"
#include "latsim/sweep/store.hpp"

namespace latsim::sweep {

/// Reads every finished run's summary (on `threads` threads) and writes
/// results.csv and results.sqlite in plan order (removing temporaries a killed
/// writer of them left, and the claim files left for finished runs). Returns
/// how many runs the tables hold; `temporaries_removed` grows by the
/// temporaries removed.
size_t write_tables(const SweepPlan& plan, const SweepStore& store, unsigned threads, size_t& temporaries_removed);

/// One line per unfinished run, in plan order: "<run id> (<axis values>)",
/// and who runs it when a live process holds its claim.
std::vector<std::string> missing_runs(const SweepPlan& plan, const SweepStore& store, RunClaims& claims);

}  // namespace latsim::sweep
