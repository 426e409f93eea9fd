// A finished run as the result tables take it: its numbers by dotted name,
// read straight from the text of its summary (a record's first line, or a
// summary.json) without building a JSON tree, which is most of the cost of
// gathering thousands of runs.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace latsim::sweep {

/// The statistics every distribution figure has (stats::Distribution::Summary), in this order.
inline constexpr std::array<const char*, 9> kDistributionStats = {"count", "mean", "stddev", "min", "p50",
                                                                  "p90",   "p99",  "p999",   "max"};

/// A distribution figure: an object under "figures" with "count" and "mean".
struct RowDistribution {
  std::string name;
  std::array<std::optional<double>, kDistributionStats.size()> stats;
  std::vector<std::pair<std::string, double>> extra;  ///< any other number it holds
};

/// A scalar figure (booleans as 0 and 1, which no headline column reads).
struct RowScalar {
  std::string name;
  double value = 0.0;
  bool boolean = false;
};

/// A model's event count and wall time (summary "models").
struct RowModel {
  std::string name;
  std::optional<double> events, wall_s;
};

/// One finished run: where it is in the plan, and every number of its summary
/// that the tables hold, in the order of the summary's (sorted) keys.
struct RunRow {
  std::string run_id;
  size_t point = 0;
  uint64_t seed = 0;
  uint64_t replication = 0;
  std::vector<nlohmann::json> values;  ///< one per sweep axis

  std::optional<double> events, wall_s, peak_rss_mb;
  std::optional<std::string> fingerprint;
  std::vector<RowScalar> scalars;  ///< under "figures", by dotted name
  std::vector<RowDistribution> distributions;
  std::vector<RowModel> models;
  std::vector<std::pair<std::string, double>> root;  ///< numbers at the summary's top level

  /// A number by dotted path as find_figure() reads the summary: under the
  /// figures first ("motion_to_photon_ms.p99"; a distribution alone stands
  /// for its mean), then at the top level ("events"). Empty when absent.
  std::optional<double> figure(const std::string& path) const;
};

/// Adds the numbers of a summary's JSON text to `row`. Throws
/// std::runtime_error on text that is not a JSON object.
void scan_summary(std::string_view text, RunRow& row);

/// The same from a summary already in memory.
void scan_summary_json(const nlohmann::json& summary, RunRow& row);

}  // namespace latsim::sweep
