#include "latsim/sweep/fidelity_table.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "latsim/results/csv_text.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/sweep/run_table.hpp"

namespace latsim::sweep {

using results::csv_field;
using scenario::number_text;

FidelityAxis parse_vary(const std::string& text) {
  const auto eq = text.find('=');
  if (text.empty() || text[0] != '/' || eq == std::string::npos)
    throw std::invalid_argument("--vary \"" + text + "\" must look like /json/pointer=v1,v2,...");
  FidelityAxis axis{text.substr(0, eq), {}};
  const std::string list = text.substr(eq + 1);
  size_t start = 0;
  while (true) {
    const size_t comma = list.find(',', start);
    axis.values.push_back(list.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (axis.values.back().empty())
      throw std::invalid_argument("--vary " + scenario::quote_value(text) + " has an empty value");
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (axis.values.size() < 2)
    throw std::invalid_argument("--vary " + scenario::quote_value(text) + " needs at least two values to compare");
  return axis;
}

void compute_errors(std::vector<FidelityLevel>& levels) {
  if (levels.empty()) return;
  const double finest = levels.back().metric;
  for (auto& level : levels) {
    level.abs_error = std::fabs(level.metric - finest);
    if (level.abs_error == 0.0) level.rel_error = 0.0;
    else if (finest == 0.0) level.rel_error = std::numeric_limits<double>::infinity();
    else level.rel_error = level.abs_error / std::fabs(finest);
  }
}

std::string fidelity_csv(const FidelityAxis& axis, const std::string& metric, const std::vector<FidelityLevel>& levels) {
  std::string text = "level," + csv_field(axis.pointer) + "," + csv_field(metric) +
                     ",abs_error,rel_error,wall_s,events,peak_rss_mb\n";
  for (size_t i = 0; i < levels.size(); ++i) {
    const auto& l = levels[i];
    text += std::to_string(i);
    for (const std::string& cell : {csv_field(l.value), number_text(l.metric), number_text(l.abs_error),
                                    number_text(l.rel_error), number_text(l.wall_s), std::to_string(l.events),
                                    number_text(l.peak_rss_mb)}) {
      text += ',';
      text += cell;
    }
    text += '\n';
  }
  return text;
}

std::string fidelity_markdown(const FidelityAxis& axis, const std::string& metric,
                              const std::vector<FidelityLevel>& levels) {
  std::string text = "# Fidelity: `" + axis.pointer + "` against `" + metric + "`\n\n" +
                     "Error is against the finest level, the last row. Wall time is the simulation's own; "
                     "memory is the run's peak resident set.\n\n"
                     "| level | " + axis.pointer + " | " + metric +
                     " | abs. error | rel. error | wall (s) | events | peak memory (MB) |\n"
                     "|---|---|---|---|---|---|---|---|\n";
  char buf[256];
  for (size_t i = 0; i < levels.size(); ++i) {
    const auto& l = levels[i];
    std::snprintf(buf, sizeof buf, "| %zu | %s | %.6g | %.3g | %.3g %% | %.3f | %llu | %.1f |\n", i, l.value.c_str(),
                  l.metric, l.abs_error, 100.0 * l.rel_error, l.wall_s, static_cast<unsigned long long>(l.events),
                  l.peak_rss_mb);
    text += buf;
  }
  return text;
}

std::string level_dir_name(size_t index, const std::string& value) {
  std::string name = std::to_string(index) + "_";
  for (char c : value) name += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' ? c : '_';
  return name;
}

}  // namespace latsim::sweep
