#include "latsim/sweep/plan.hpp"

#include "latsim/sweep/run_table.hpp"
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "latsim/des/random.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/scenario/json_text.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/sweep/run_table.hpp"

namespace latsim::sweep {

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

// Plans past this size are almost certainly a typo in a range step.
constexpr size_t kMaxRuns = 1'000'000;

std::string describe_point(const std::vector<SweepAxis>& axes, const std::vector<size_t>& indices) {
  std::string text;
  for (size_t a = 0; a < axes.size(); ++a) {
    if (a) text += ", ";
    text += axes[a].pointer + "=" + value_text(axes[a].values[indices[a]]);
  }
  return text;
}

void check_keys(const Json& object, std::initializer_list<const char*> allowed, const fs::path& file,
                const std::string& pointer) {
  for (auto it = object.begin(); it != object.end(); ++it) {
    bool known = false;
    std::string list;
    for (const char* key : allowed) {
      known = known || it.key() == key;
      list += std::string(list.empty() ? "" : ", ") + key;
    }
    if (!known)
      throw SweepError(file, scenario::join_pointer(pointer, it.key()), "unknown key; expected one of " + list);
  }
}

uint64_t non_negative_integer(const Json& sweep, const char* key, uint64_t def, uint64_t lo, uint64_t hi,
                              const fs::path& file) {
  if (!sweep.contains(key)) return def;
  const Json& v = sweep[key];
  const bool integral = v.is_number_unsigned() || (v.is_number_integer() && v.get<int64_t>() >= 0);
  if (!integral || v.get<uint64_t>() < lo || v.get<uint64_t>() > hi)
    throw SweepError(file, std::string("/") + key,
                     "expected an integer from " + std::to_string(lo) + " to " + std::to_string(hi));
  return v.get<uint64_t>();
}

// The base scenario with its includes merged, as a plain document.
Json load_base(const fs::path& base_file, const fs::path& sweep_file) {
  try {
    return scenario::ScenarioDocument::load(base_file, {}, &run::scenario_schema()).json();
  } catch (const scenario::ScenarioError& e) {
    throw SweepError(sweep_file, "/base", e.line(base_file));
  }
}

void apply_overrides(Json& doc, const Json& sweep, const fs::path& file) {
  if (!sweep.contains("overrides")) return;
  const Json& overrides = sweep["overrides"];
  if (!overrides.is_object())
    throw SweepError(file, "/overrides", "expected an object of {\"/json/pointer\": value}");
  for (auto it = overrides.begin(); it != overrides.end(); ++it) {
    const std::string where = scenario::join_pointer("/overrides", it.key());
    if (it.key().empty() || it.key()[0] != '/')
      throw SweepError(file, where, "an override's key must be a JSON pointer such as /display/refresh_hz");
    try {
      scenario::apply_override(doc, it.key() + "=" + it.value().dump());
    } catch (const scenario::ScenarioError& e) {
      throw SweepError(file, where, e.message());
    }
  }
}

SweepAxis read_axis(const Json& axis, const std::string& where, const fs::path& file, bool allow_repeats) {
  if (!axis.is_object()) throw SweepError(file, where, "an axis must be an object with \"pointer\" and \"values\" or \"range\"");
  check_keys(axis, {"pointer", "values", "range", "label"}, file, where);
  if (!axis.contains("pointer") || !axis["pointer"].is_string())
    throw SweepError(file, where + "/pointer", "expected a JSON pointer string such as \"/display/refresh_hz\"");
  SweepAxis result;
  result.pointer = axis["pointer"].get<std::string>();
  if (result.pointer.empty() || result.pointer[0] != '/')
    throw SweepError(file, where + "/pointer", "\"" + result.pointer + "\" is not a JSON pointer (it must start with /)");
  try {
    (void)Json::json_pointer(result.pointer);
  } catch (const Json::exception& e) {
    throw SweepError(file, where + "/pointer", "\"" + result.pointer + "\" is not a valid JSON pointer");
  }
  if (axis.contains("label")) {
    if (!axis["label"].is_string() || axis["label"].get<std::string>().empty() ||
        axis["label"].get<std::string>().size() > 200)
      throw SweepError(file, where + "/label", "expected a name of 1 to 200 characters for tables and plots");
    result.label = axis["label"].get<std::string>();
  }
  const bool has_values = axis.contains("values"), has_range = axis.contains("range");
  if (has_values == has_range) throw SweepError(file, where, "give exactly one of \"values\" and \"range\"");
  if (has_values) {
    const Json& values = axis["values"];
    if (!values.is_array() || values.empty())
      throw SweepError(file, where + "/values", "expected a non-empty array of values");
    result.values.assign(values.begin(), values.end());
  } else {
    result.values = expand_range(axis["range"], file, where + "/range");
    result.from_range = true;
  }
  // A repeated value would run a point twice, except in zip mode, where the
  // other axes tell the points apart (two points that are the same scenario
  // are still caught when the runs are planned).
  std::set<std::string> seen;
  for (size_t i = 0; i < result.values.size() && !allow_repeats; ++i)
    if (!seen.insert(result.values[i].dump()).second)
      throw SweepError(file, where + (has_values ? "/values/" + std::to_string(i) : "/range"),
                       "value " + value_text(result.values[i]) + " appears twice on this axis");
  return result;
}

}  // namespace

SweepError::SweepError(const fs::path& file, const std::string& pointer, const std::string& message)
    : std::runtime_error(scenario::readable(file.string(), 2 * scenario::kQuotedChars) + ": " +
                         (pointer.empty() ? "" : scenario::readable_pointer(pointer) + ": ") + scenario::readable(message)),
      pointer_(pointer),
      message_(message) {}

std::vector<Json> expand_range(const Json& range, const fs::path& file, const std::string& pointer) {
  if (!range.is_object()) throw SweepError(file, pointer, "expected {\"from\": a, \"to\": b, \"step\": s}");
  check_keys(range, {"from", "to", "step"}, file, pointer);
  for (const char* key : {"from", "to", "step"})
    if (!range.contains(key) || !range[key].is_number())
      throw SweepError(file, pointer + "/" + key, "expected a number");
  const double from = range["from"].get<double>(), to = range["to"].get<double>(), step = range["step"].get<double>();
  if (!(step != 0.0) || !std::isfinite(step)) throw SweepError(file, pointer + "/step", "the step must be non-zero");
  const double span = (to - from) / step;
  if (span < 0.0) throw SweepError(file, pointer + "/step", "stepping from \"from\" never reaches \"to\"");
  // A small tolerance keeps "to" itself when from + n*step lands on it up to rounding.
  const double count_d = std::floor(span + 1e-9) + 1.0;
  if (count_d > 100000.0) throw SweepError(file, pointer, "the range has more than 100000 values");
  const auto count = static_cast<size_t>(count_d);
  const bool integral = range["from"].is_number_integer() && range["step"].is_number_integer();
  std::vector<Json> values;
  values.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    // Each value from its index, never by adding the step again and again.
    if (integral) values.emplace_back(range["from"].get<int64_t>() + static_cast<int64_t>(i) * range["step"].get<int64_t>());
    else values.emplace_back(from + static_cast<double>(i) * step);
  }
  return values;
}

std::vector<std::vector<size_t>> expand_points(const std::vector<size_t>& axis_sizes, bool zip) {
  std::vector<std::vector<size_t>> points;
  // No axis: one point, the base scenario itself (its replications).
  if (axis_sizes.empty()) return {std::vector<size_t>{}};
  if (zip) {
    for (size_t i = 0; i < axis_sizes.front(); ++i) points.emplace_back(axis_sizes.size(), i);
    return points;
  }
  std::vector<size_t> current(axis_sizes.size(), 0);
  for (size_t n : axis_sizes)
    if (n == 0) return points;
  while (true) {
    points.push_back(current);
    // Odometer increment: the last axis varies fastest.
    size_t a = axis_sizes.size();
    while (a > 0) {
      --a;
      if (++current[a] < axis_sizes[a]) break;
      current[a] = 0;
      if (a == 0) return points;
    }
  }
}

std::string run_id_of(const Json& scenario, uint64_t seed, uint64_t replication) {
  // nlohmann::json keeps object keys sorted, so equal scenarios dump equally.
  // FNV-1a alone barely changes the high bits when only the last byte differs
  // (replications); the splitmix64 finaliser spreads every bit over the id.
  const std::string text =
      scenario.dump() + "\nseed=" + std::to_string(seed) + "\nreplication=" + std::to_string(replication);
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(des::mix64(des::fnv1a64(text))));
  return buf;
}

std::string value_text(const Json& value) {
  return value.is_string() ? value.get<std::string>() : value.dump();
}

SweepPlan SweepPlan::load(const fs::path& sweep_file, const ResolveDefaults& resolve) {
  Json sweep;
  try {
    sweep = scenario::read_json_file(sweep_file, "sweep file");
  } catch (const scenario::ScenarioError& e) {
    throw SweepError(sweep_file, e.pointer(), e.message());
  }
  return from_json(sweep, sweep_file, resolve);
}

namespace {

// The "keep" key: a string as --keep takes it.
std::optional<KeepPolicy> read_keep(const Json& sweep, size_t run_count, const fs::path& file) {
  if (!sweep.contains("keep")) return std::nullopt;
  if (!sweep["keep"].is_string())
    throw SweepError(file, "/keep", "expected a string: \"figures\", \"first\", \"all\" or \"runs=I,J,...\"");
  try {
    KeepPolicy keep = KeepPolicy::parse(sweep["keep"].get<std::string>());
    keep.check_runs(run_count);
    return keep;
  } catch (const std::invalid_argument& e) {
    throw SweepError(file, "/keep", e.what());
  }
}

}  // namespace

SweepPlan SweepPlan::from_json(const Json& sweep, const fs::path& sweep_file, const ResolveDefaults& resolve) {
  const fs::path& file = sweep_file;
  if (!sweep.is_object()) throw SweepError(file, "", "a sweep must be a JSON object");
  check_keys(sweep, {"description", "base", "axes", "mode", "replications", "seed", "overrides", "keep", "figures"},
             file, "");
  SweepPlan plan;
  plan.sweep_file_ = sweep_file;
  if (!sweep.contains("base") || !sweep["base"].is_string())
    throw SweepError(file, "/base", "expected the path of the base scenario, relative to the sweep file");
  plan.base_file_ = sweep["base"].get<std::string>();
  if (plan.base_file_.is_relative()) plan.base_file_ = sweep_file.parent_path() / plan.base_file_;
  Json doc = load_base(plan.base_file_, file);
  apply_overrides(doc, sweep, file);
  const uint64_t max_seed = std::numeric_limits<uint64_t>::max();
  const uint64_t base_seed = doc.contains("seed") && doc["seed"].is_number_unsigned() ? doc["seed"].get<uint64_t>() : 1;
  doc["seed"] = non_negative_integer(sweep, "seed", base_seed, 0, max_seed, file);
  plan.replications_ = non_negative_integer(sweep, "replications", 1, 1, kMaxRuns, file);
  // The report's columns, by their results.csv names (docs/sweeps.md).
  if (sweep.contains("figures")) {
    const Json& figures = sweep["figures"];
    if (!figures.is_array() || figures.empty())
      throw SweepError(file, "/figures", "expected a non-empty array of results.csv column names");
    std::set<std::string> known;
    for (const auto& column : headline_columns())
      if (column.name != "events" && column.name != "wall_s") known.insert(column.name);
    for (size_t i = 0; i < figures.size(); ++i) {
      if (!figures[i].is_string() || !known.count(figures[i].get<std::string>())) {
        std::string names;
        for (const auto& n : known) names += (names.empty() ? "" : ", ") + n;
        throw SweepError(file, "/figures/" + std::to_string(i), "expected one of " + names);
      }
      plan.figures_.push_back(figures[i].get<std::string>());
    }
  }

  std::string mode = "cartesian";
  if (sweep.contains("mode") && sweep["mode"].is_string()) mode = sweep["mode"].get<std::string>();
  else if (sweep.contains("mode")) mode.clear();
  if (mode != "cartesian" && mode != "zip") throw SweepError(file, "/mode", "expected \"cartesian\" or \"zip\"");
  // An empty array is one point: the base scenario, replicated.
  if (!sweep.contains("axes") || !sweep["axes"].is_array())
    throw SweepError(file, "/axes", "expected an array of axes ([] for replications of the base scenario alone)");

  std::optional<Json> resolved;
  std::set<std::string> pointers;
  for (size_t i = 0; i < sweep["axes"].size(); ++i) {
    const std::string where = "/axes/" + std::to_string(i);
    SweepAxis axis = read_axis(sweep["axes"][i], where, file, mode == "zip");
    if (!pointers.insert(axis.pointer).second)
      throw SweepError(file, where + "/pointer", "\"" + axis.pointer + "\" is already swept by an earlier axis");
    const Json::json_pointer ptr(axis.pointer);
    if (!doc.contains(ptr)) {
      // Not in the file, but maybe a key the scenario reader fills with a default.
      if (!resolved) {
        try {
          resolved = resolve(doc, plan.base_dir());
        } catch (const scenario::ScenarioError& e) {
          throw SweepError(file, "/base", e.line(plan.base_file_));
        }
      }
      if (!resolved->contains(ptr))
        throw SweepError(file, where + "/pointer",
                         "\"" + axis.pointer + "\" does not exist in the base scenario " + plan.base_file_.string());
    }
    if (mode == "zip" && i > 0 && axis.values.size() != plan.axes_[0].values.size())
      throw SweepError(file, where, "zip mode needs axes of equal length: axis 0 has " +
                                        std::to_string(plan.axes_[0].values.size()) + " values, this one " +
                                        std::to_string(axis.values.size()));
    plan.axes_.push_back(std::move(axis));
  }

  std::vector<size_t> sizes;
  double total = static_cast<double>(plan.replications_);
  for (const auto& axis : plan.axes_) {
    sizes.push_back(axis.values.size());
    if (mode == "cartesian") total *= static_cast<double>(axis.values.size());
  }
  if (mode == "zip" && !sizes.empty()) total *= static_cast<double>(sizes.front());
  if (total > static_cast<double>(kMaxRuns))
    throw SweepError(file, "/axes", "the sweep expands to more than " + std::to_string(kMaxRuns) + " runs");

  const auto points = expand_points(sizes, mode == "zip");
  plan.point_count_ = points.size();
  std::map<std::string, size_t> seen_ids;
  for (size_t p = 0; p < points.size(); ++p) {
    Json scenario = doc;
    for (size_t a = 0; a < plan.axes_.size(); ++a)
      scenario[Json::json_pointer(plan.axes_[a].pointer)] = plan.axes_[a].values[points[p][a]];
    const uint64_t seed = scenario["seed"].is_number_unsigned() ? scenario["seed"].get<uint64_t>() : 0;
    for (uint64_t r = 0; r < plan.replications_; ++r) {
      SweepRun run;
      run.index = plan.runs_.size();
      run.point = p;
      run.value_indices = points[p];
      run.seed = seed;
      run.replication = r;
      run.run_id = run_id_of(scenario, seed, r);
      auto [it, fresh] = seen_ids.emplace(run.run_id, p);
      if (!fresh)
        throw SweepError(file, "/axes", "sweep points " + describe_point(plan.axes_, points[it->second]) + " and " +
                                            describe_point(plan.axes_, points[p]) + " run the same scenario");
      run.scenario = scenario;
      plan.runs_.push_back(std::move(run));
    }
  }
  plan.keep_ = read_keep(sweep, plan.runs_.size(), file);
  return plan;
}

fs::path SweepPlan::base_dir() const {
  fs::path dir = base_file_.parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

std::string SweepPlan::describe(const SweepRun& run) const { return describe_point(axes_, run.value_indices); }

std::string SweepPlan::value_pointer(size_t axis, size_t value_index) const {
  const std::string where = "/axes/" + std::to_string(axis);
  return axes_[axis].from_range ? where + "/range" : where + "/values/" + std::to_string(value_index);
}

Json SweepPlan::to_json() const {
  Json axes = Json::array();
  for (const auto& axis : axes_) {
    axes.push_back({{"pointer", axis.pointer}, {"values", axis.values}});
    if (!axis.label.empty()) axes.back()["label"] = axis.label;
  }
  Json runs = Json::array();
  for (const auto& run : runs_) {
    Json values = Json::array();
    for (size_t a = 0; a < axes_.size(); ++a) values.push_back(axes_[a].values[run.value_indices[a]]);
    runs.push_back({{"run_id", run.run_id}, {"point", run.point}, {"replication", run.replication},
                    {"seed", run.seed}, {"values", values}});
  }
  Json plan = {{"sweep_file", sweep_file_.string()}, {"base", base_file_.string()}, {"axes", axes},
               {"replications", replications_}, {"points", point_count_}, {"runs", runs}};
  if (!figures_.empty()) plan["figures"] = figures_;
  return plan;
}

}  // namespace latsim::sweep
