// Tables of finished runs: the headline figures of each run's summary.json,
// flattened for results.csv, results.sqlite and the fidelity table.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/sweep/run_row.hpp"

namespace latsim::sweep {

/// One headline column: its name in the tables and where it comes from.
struct HeadlineColumn {
  std::string name;    ///< e.g. "mtp_p99_ms"
  std::string figure;  ///< dotted path looked up by find_figure, e.g. "motion_to_photon_ms.p99"
};

/// The headline columns of results.csv, in order.
std::vector<HeadlineColumn> headline_columns();

/// A number by dotted path: first under the summary's "figures", then from its
/// root ("events", "figures.frame_rate_hz"). A distribution without a stat
/// ("render_latency_ms") means its mean. Empty when absent or not a number.
std::optional<double> find_figure(const nlohmann::json& summary, const std::string& path);

/// Every name a sweep file's "figures" (and `latsim report --figures`) may
/// choose: the results.csv columns (but events and wall_s), then every
/// figure the registry declares that a table can hold, by its figures.json
/// path: a count, number or flag by name (placeholders other than <n>
/// filled in), a distribution's statistics as name.stat.
const std::vector<std::string>& choosable_figures();

/// The registry's columns, then one per chosen figure that is none of
/// them (named and looked up by its path).
std::vector<HeadlineColumn> table_columns(const std::vector<std::string>& chosen);

/// results.csv: run_id, point, one column per axis pointer, seed, replication,
/// then the registry's columns and those of the chosen figures that are none
/// of them; one row per run, in the order given.
std::string results_csv(const std::vector<std::string>& axis_pointers, const std::vector<RunRow>& rows,
                        const std::vector<std::string>& chosen = {});
/// results.csv's header line, and one row appended to the text after it.
std::string results_csv_header(const std::vector<std::string>& axis_pointers,
                               const std::vector<std::string>& chosen = {});
void append_results_csv_row(std::string& text, const RunRow& row);
void append_results_csv_row(std::string& text, const RunRow& row, const std::vector<HeadlineColumn>& columns);

/// A scalar figure of a run, flattened to a dotted name.
struct FigureValue {
  std::string name;
  double value;
};

/// One statistic of a distribution figure (count, mean, p99, ...).
struct DistributionStat {
  std::string name;
  std::string stat;
  double value;
};

/// One histogram bucket of a distribution figure.
struct HistogramBucket {
  std::string name;
  size_t bucket;
  double edge;
  double count;
};

/// Every number under a summary's "figures", sorted into scalars,
/// distribution statistics and histogram buckets.
struct FlatFigures {
  std::vector<FigureValue> scalars;
  std::vector<DistributionStat> stats;
  std::vector<HistogramBucket> buckets;
};

FlatFigures flatten_figures(const nlohmann::json& figures);

}  // namespace latsim::sweep
