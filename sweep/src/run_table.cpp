#include "latsim/sweep/run_table.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "latsim/results/csv_text.hpp"
#include "latsim/results/figure_registry.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/sweep/plan.hpp"
#include "latsim/sweep/run_row.hpp"

namespace latsim::sweep {

namespace {

using Json = nlohmann::json;

const Json* walk(const Json& root, const std::string& path) {
  const Json* node = &root;
  size_t start = 0;
  while (start <= path.size()) {
    const size_t dot = path.find('.', start);
    const std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (!node->is_object() || !node->contains(key)) return nullptr;
    node = &(*node)[key];
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return node;
}

std::optional<double> as_number(const Json* node) {
  if (!node) return std::nullopt;
  // A distribution named without a statistic stands for its mean.
  if (node->is_object() && node->contains("mean")) node = &(*node)["mean"];
  if (!node->is_number()) return std::nullopt;
  return node->get<double>();
}

bool is_distribution(const Json& node) { return node.is_object() && node.contains("count") && node.contains("mean"); }

void flatten(const Json& node, const std::string& name, FlatFigures& out) {
  if (node.is_number() || node.is_boolean()) {
    out.scalars.push_back({name, node.is_boolean() ? (node.get<bool>() ? 1.0 : 0.0) : node.get<double>()});
  } else if (is_distribution(node)) {
    for (auto it = node.begin(); it != node.end(); ++it) {
      if (it.value().is_number()) out.stats.push_back({name, it.key(), it.value().get<double>()});
    }
    if (node.contains("histogram") && node["histogram"].is_array()) {
      const Json& hist = node["histogram"];
      for (size_t b = 0; b < hist.size(); ++b)
        if (hist[b].is_array() && hist[b].size() == 2 && hist[b][0].is_number() && hist[b][1].is_number())
          out.buckets.push_back({name, b, hist[b][0].get<double>(), hist[b][1].get<double>()});
    }
  } else if (node.is_object()) {
    for (auto it = node.begin(); it != node.end(); ++it) flatten(it.value(), name.empty() ? it.key() : name + "." + it.key(), out);
  }
}

}  // namespace

std::vector<HeadlineColumn> headline_columns() {
  // The registry's columns, in its order (results/figure_registry.json).
  std::vector<HeadlineColumn> columns;
  for (const results::FigureColumn& c : results::FigureRegistry::builtin().columns()) columns.push_back({c.name, c.figure});
  return columns;
}

namespace {

// A declared name with its placeholders filled in by every word they stand
// for; an index (<n>) cannot be listed, so such names are left out.
void expand_name(const results::FigureRegistry& registry, const std::string& name, std::vector<std::string>& out) {
  const size_t open = name.find('<');
  if (open == std::string::npos) {
    out.push_back(name);
    return;
  }
  const size_t close = name.find('>', open);
  const std::string word = name.substr(open + 1, close - open - 1);
  if (word == "n") return;
  for (const std::string& value : registry.placeholder(word))
    expand_name(registry, name.substr(0, open) + value + name.substr(close + 1), out);
}

std::vector<std::string> make_choosable() {
  std::vector<std::string> names;
  std::set<std::string> seen;
  auto add = [&](const std::string& name) {
    if (seen.insert(name).second) names.push_back(name);
  };
  for (const auto& column : headline_columns())
    if (column.name != "events" && column.name != "wall_s") add(column.name);
  const results::FigureRegistry& registry = results::FigureRegistry::builtin();
  for (const results::FigureDecl& d : registry.figures()) {
    const bool scalar = d.kind == "count" || d.kind == "number" || d.kind == "flag";
    if (d.family == "summary" || (!scalar && d.kind != "distribution")) continue;
    std::vector<std::string> expanded;
    expand_name(registry, d.name, expanded);
    for (const std::string& name : expanded) {
      if (scalar) add(name);
      else
        for (const char* stat : kDistributionStats) add(name + "." + stat);
    }
  }
  return names;
}

}  // namespace

const std::vector<std::string>& choosable_figures() {
  static const std::vector<std::string> names = make_choosable();
  return names;
}

std::vector<HeadlineColumn> table_columns(const std::vector<std::string>& chosen) {
  std::vector<HeadlineColumn> columns = headline_columns();
  for (const std::string& name : chosen) {
    const bool known = std::any_of(columns.begin(), columns.end(), [&](const HeadlineColumn& c) {
      return c.name == name || c.figure == name;
    });
    if (!known) columns.push_back({name, name});
  }
  return columns;
}

std::optional<double> find_figure(const Json& summary, const std::string& path) {
  if (summary.contains("figures")) {
    if (auto v = as_number(walk(summary["figures"], path))) return v;
  }
  return as_number(walk(summary, path));
}

std::string results_csv_header(const std::vector<std::string>& axis_pointers, const std::vector<std::string>& chosen) {
  // Cells are appended one by one: building "," + cell temporaries trips
  // GCC 12's -Wrestrict false positive at -O2.
  std::string text = "run_id,point";
  for (const auto& pointer : axis_pointers) {
    text += ',';
    text += results::csv_field(pointer);
  }
  text += ",seed,replication";
  for (const auto& column : table_columns(chosen)) {
    text += ',';
    text += column.name;
  }
  text += '\n';
  return text;
}

void append_results_csv_row(std::string& text, const RunRow& row) {
  static const std::vector<HeadlineColumn> columns = headline_columns();
  append_results_csv_row(text, row, columns);
}

void append_results_csv_row(std::string& text, const RunRow& row, const std::vector<HeadlineColumn>& columns) {
  auto cell = [&text](const std::string& value) {
    text += ',';
    text += value;
  };
  text += row.run_id;
  cell(std::to_string(row.point));
  for (const auto& value : row.values) cell(results::csv_field(value_text(value)));
  cell(std::to_string(row.seed));
  cell(std::to_string(row.replication));
  for (const auto& column : columns) {
    const auto v = row.figure(column.figure);
    cell(v ? scenario::number_text(*v) : std::string());
  }
  text += '\n';
}

std::string results_csv(const std::vector<std::string>& axis_pointers, const std::vector<RunRow>& rows,
                        const std::vector<std::string>& chosen) {
  std::string text = results_csv_header(axis_pointers, chosen);
  const std::vector<HeadlineColumn> columns = table_columns(chosen);
  for (const auto& row : rows) append_results_csv_row(text, row, columns);
  return text;
}

FlatFigures flatten_figures(const Json& figures) {
  FlatFigures out;
  flatten(figures, "", out);
  return out;
}

}  // namespace latsim::sweep
