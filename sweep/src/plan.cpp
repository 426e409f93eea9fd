#include "latsim/sweep/plan.hpp"

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
#include "latsim/sweep/sweep_file.hpp"

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

// The base scenario with its includes merged, as a plain document.
Json load_base(const fs::path& base_file, const fs::path& sweep_file) {
  try {
    return scenario::ScenarioDocument::load(base_file, {}, &run::scenario_schema()).json();
  } catch (const scenario::ScenarioError& e) {
    throw SweepError(sweep_file, "/base", e.line(base_file));
  }
}

void apply_overrides(Json& doc, const Json& overrides, const fs::path& file) {
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

SweepAxis read_axis(const SweepFileAxis& axis, const std::string& where, const fs::path& file, bool allow_repeats) {
  SweepAxis result;
  result.pointer = axis.pointer;
  try {
    (void)Json::json_pointer(result.pointer);
  } catch (const Json::exception& e) {
    throw SweepError(file, where + "/pointer", "\"" + result.pointer + "\" is not a valid JSON pointer");
  }
  result.label = axis.label;
  const bool has_values = !axis.values.is_null();
  if (has_values) {
    result.values.assign(axis.values.begin(), axis.values.end());
  } else {
    result.values = expand_range(axis.range, file, where + "/range");
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
    // The very line a scenario error prints: file, pointer, message.
    : std::runtime_error(scenario::ScenarioError(pointer, message).line(file)),
      pointer_(pointer),
      message_(message) {}

std::vector<Json> expand_range(const Json& range, const fs::path& file, const std::string& pointer) {
  if (!range.is_object()) throw SweepError(file, pointer, "expected {\"from\": a, \"to\": b, \"step\": s}");
  for (auto it = range.begin(); it != range.end(); ++it)
    if (it.key() != "from" && it.key() != "to" && it.key() != "step")
      throw SweepError(file, scenario::join_pointer(pointer, it.key()), "unknown key; expected one of from, to, step");
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
  return RunIds(scenario).of(seed, replication);
}

// nlohmann::json keeps object keys sorted, so equal scenarios dump equally.
RunIds::RunIds(const Json& scenario) : prefix_hash_(des::fnv1a64(scenario.dump())) {}

std::string RunIds::of(uint64_t seed, uint64_t replication) const {
  // FNV-1a of the dump followed by the suffix, continued from the dump's
  // state. FNV-1a alone barely changes the high bits when only the last byte
  // differs (replications); the splitmix64 finaliser spreads every bit.
  const std::string suffix = "\nseed=" + std::to_string(seed) + "\nreplication=" + std::to_string(replication);
  uint64_t h = prefix_hash_;
  for (const char c : suffix) {
    h ^= static_cast<uint64_t>(static_cast<unsigned char>(c));
    h *= 0x100000001b3ULL;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(des::mix64(h)));
  return buf;
}

std::string value_text(const Json& value) {
  return value.is_string() ? value.get<std::string>() : value.dump();
}

SweepPlan SweepPlan::load(const fs::path& sweep_file, const ResolveDefaults& resolve, const std::atomic<bool>* stop) {
  Json sweep;
  try {
    sweep = scenario::read_json_file(sweep_file, "sweep file");
  } catch (const scenario::ScenarioError& e) {
    throw SweepError(sweep_file, e.pointer(), e.message());
  }
  return from_json(sweep, sweep_file, resolve, stop);
}

namespace {

// The "keep" key: a string as --keep takes it.
std::optional<KeepPolicy> read_keep(const SweepFile& f, size_t run_count, const fs::path& file) {
  if (f.keep.empty()) return std::nullopt;
  try {
    KeepPolicy keep = KeepPolicy::parse(f.keep);
    keep.check_runs(run_count);
    return keep;
  } catch (const std::invalid_argument& e) {
    throw SweepError(file, "/keep", e.what());
  }
}

// The axes, each checked against the base scenario (resolved with its
// defaults only when a pointer is not in the file itself).
std::vector<SweepAxis> read_axes(const SweepFile& f, const Json& doc, const fs::path& file, const fs::path& base_file,
                                 const fs::path& base_dir, const ResolveDefaults& resolve) {
  const bool zip = f.mode == SweepFile::Mode::zip;
  std::vector<SweepAxis> axes;
  std::optional<Json> resolved;
  std::set<std::string> pointers;
  for (size_t i = 0; i < f.axes.size(); ++i) {
    const std::string where = "/axes/" + std::to_string(i);
    SweepAxis axis = read_axis(f.axes[i], where, file, zip);
    if (!pointers.insert(axis.pointer).second)
      throw SweepError(file, where + "/pointer", "\"" + axis.pointer + "\" is already swept by an earlier axis");
    const Json::json_pointer ptr(axis.pointer);
    if (!doc.contains(ptr)) {
      // Not in the file, but maybe a key the scenario reader fills with a default.
      if (!resolved) {
        try {
          resolved = resolve(doc, base_dir);
        } catch (const scenario::ScenarioError& e) {
          throw SweepError(file, "/base", e.line(base_file));
        }
      }
      if (!resolved->contains(ptr))
        throw SweepError(file, where + "/pointer",
                         "\"" + axis.pointer + "\" does not exist in the base scenario " + base_file.string());
    }
    if (zip && i > 0 && axis.values.size() != axes[0].values.size())
      throw SweepError(file, where, "zip mode needs axes of equal length: axis 0 has " +
                                        std::to_string(axes[0].values.size()) + " values, this one " +
                                        std::to_string(axis.values.size()));
    axes.push_back(std::move(axis));
  }
  return axes;
}

}  // namespace

SweepPlan SweepPlan::from_json(const Json& sweep, const fs::path& sweep_file, const ResolveDefaults& resolve,
                               const std::atomic<bool>* stop) {
  const fs::path& file = sweep_file;
  const SweepFile f = read_sweep_file(sweep, file);
  SweepPlan plan;
  plan.sweep_file_ = sweep_file;
  plan.base_file_ = f.base;
  if (plan.base_file_.is_relative()) plan.base_file_ = sweep_file.parent_path() / plan.base_file_;
  Json doc = load_base(plan.base_file_, file);
  apply_overrides(doc, f.overrides, file);
  const uint64_t base_seed = doc.contains("seed") && doc["seed"].is_number_unsigned() ? doc["seed"].get<uint64_t>() : 1;
  doc["seed"] = f.seed.is_null() ? base_seed : f.seed.get<uint64_t>();
  plan.replications_ = static_cast<uint64_t>(f.replications);
  plan.figures_ = f.figures;
  plan.axes_ = read_axes(f, doc, file, plan.base_file_, plan.base_dir(), resolve);

  const bool zip = f.mode == SweepFile::Mode::zip;
  std::vector<size_t> sizes;
  double total = static_cast<double>(plan.replications_);
  for (const auto& axis : plan.axes_) {
    sizes.push_back(axis.values.size());
    if (!zip) total *= static_cast<double>(axis.values.size());
  }
  if (zip && !sizes.empty()) total *= static_cast<double>(sizes.front());
  if (total > static_cast<double>(kMaxRuns))
    throw SweepError(file, "/axes", "the sweep expands to more than " + std::to_string(kMaxRuns) + " runs");

  const auto points = expand_points(sizes, zip);
  plan.points_.reserve(points.size());
  plan.runs_.reserve(points.size() * plan.replications_);
  std::map<std::string, size_t> seen_ids;
  for (size_t p = 0; p < points.size(); ++p) {
    if (stop && stop->load(std::memory_order_relaxed)) throw PlanStopped();
    Json scenario = doc;
    for (size_t a = 0; a < plan.axes_.size(); ++a)
      scenario[Json::json_pointer(plan.axes_[a].pointer)] = plan.axes_[a].values[points[p][a]];
    const uint64_t seed = scenario["seed"].is_number_unsigned() ? scenario["seed"].get<uint64_t>() : 0;
    const RunIds ids(scenario);
    for (uint64_t r = 0; r < plan.replications_; ++r) {
      SweepRun run;
      run.index = plan.runs_.size();
      run.point = p;
      run.seed = seed;
      run.replication = r;
      run.run_id = ids.of(seed, r);
      auto [it, fresh] = seen_ids.emplace(run.run_id, p);
      if (!fresh)
        throw SweepError(file, "/axes", "sweep points " + describe_point(plan.axes_, points[it->second]) + " and " +
                                            describe_point(plan.axes_, points[p]) + " run the same scenario");
      plan.runs_.push_back(std::move(run));
    }
    plan.points_.push_back(SweepPoint{points[p], std::move(scenario)});
  }
  plan.keep_ = read_keep(f, plan.runs_.size(), file);
  return plan;
}

fs::path SweepPlan::base_dir() const {
  fs::path dir = base_file_.parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

std::string SweepPlan::describe(const SweepRun& run) const {
  return describe_point(axes_, points_[run.point].value_indices);
}

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
    for (size_t a = 0; a < axes_.size(); ++a) values.push_back(value(run, a));
    runs.push_back({{"run_id", run.run_id}, {"point", run.point}, {"replication", run.replication},
                    {"seed", run.seed}, {"values", values}});
  }
  Json plan = {{"sweep_file", sweep_file_.string()}, {"base", base_file_.string()}, {"axes", axes},
               {"replications", replications_}, {"points", points_.size()}, {"runs", runs}};
  if (!figures_.empty()) plan["figures"] = figures_;
  return plan;
}

}  // namespace latsim::sweep
