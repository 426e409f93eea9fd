// Building latsim compare's rows: shared by the PresentMon rows and the
// runtime-statistics rows.
#pragma once

#include <string>
#include <vector>

#include "compare_run.hpp"
#include "latsim/capture/runtime_stats.hpp"
#include "latsim/sweep/compare.hpp"

namespace latsim::sweep {

/// One side's values, with their statistics; `total_only`: a single figure, not a sample.
CompareSide compare_side(std::string column, std::vector<double> values, bool total_only);
CompareRow compare_row(std::string key, std::string label, CompareSide capture, CompareSide run, Standing standing,
                       std::string note);
/// Sets the row's KS distance (both sides samples), verdict and agreement:
/// samples agree at a KS distance of at most ks_threshold; a total agrees
/// within mean_tolerance of the capture's mean, or `floor` when that is
/// larger; rows not predicted say why they are left out.
void compare_judge(CompareRow& r, const CompareRequest& q, double floor, const std::string& unit);

/// The rows of a PresentMon capture against a run's presentmon.csv (or another capture).
void presentmon_rows(const capture::PresentMonProcess& cap, const RunSide& run, const CompareRequest& q, Comparison& out);
/// The rows of a runtime's statistics against a run.
void runtime_rows(const capture::RuntimeStats& cap, const RunSide& run, const CompareRequest& q, Comparison& out);

}  // namespace latsim::sweep
