// The accuracy/cost table of `latsim fidelity`: one metric at several levels
// of a fidelity knob, its error against the finest level, and what each level cost.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace latsim::sweep {

/// A --vary argument split up: "/display/scanout=field,line,pixel".
struct FidelityAxis {
  std::string pointer;
  std::vector<std::string> values;  ///< coarsest first; the last is the reference
};

/// Parses "/pointer=v1,v2,..."; throws std::invalid_argument saying what is wrong.
FidelityAxis parse_vary(const std::string& text);

/// One level's measurements.
struct FidelityLevel {
  std::string value;
  double metric = 0.0;
  double wall_s = 0.0;       ///< simulation wall time from the run's summary
  uint64_t events = 0;
  double peak_rss_mb = 0.0;  ///< the run's process peak resident memory
  double abs_error = 0.0;    ///< |metric - metric at the finest level|
  double rel_error = 0.0;    ///< abs_error / |finest|; 0 when equal, infinite when the finest is 0
};

/// Fills abs_error and rel_error against the last level. The finest level's
/// errors are exactly zero (x - x is 0 for every finite x).
void compute_errors(std::vector<FidelityLevel>& levels);

/// fidelity.csv: level, value, metric, abs_error, rel_error, wall_s, events, peak_rss_mb.
std::string fidelity_csv(const FidelityAxis& axis, const std::string& metric, const std::vector<FidelityLevel>& levels);

/// fidelity.md: the same as a Markdown table with a heading naming the knob and metric.
std::string fidelity_markdown(const FidelityAxis& axis, const std::string& metric,
                              const std::vector<FidelityLevel>& levels);

/// A directory name for a level: "<index>_<value with unsafe characters replaced>".
std::string level_dir_name(size_t index, const std::string& value);

}  // namespace latsim::sweep
