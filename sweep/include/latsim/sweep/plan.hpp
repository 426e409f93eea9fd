// A parameter sweep: a base scenario, axes of values at JSON pointers, and the
// list of runs (sweep point x replication) they expand to.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/sweep/keep.hpp"

namespace latsim::sweep {

/// One swept parameter: a JSON pointer into the scenario and the values it takes.
struct SweepAxis {
  std::string pointer;               ///< where in the scenario the value goes
  std::vector<nlohmann::json> values;
  bool from_range = false;           ///< values came from {"from", "to", "step"}
  std::string label;                 ///< what tables and plots call it (empty: the pointer)
};

/// One sweep point: a combination of axis values and the scenario it makes.
struct SweepPoint {
  std::vector<size_t> value_indices;  ///< per axis, the index into its values
  nlohmann::json scenario;            ///< base + overrides + this point's values
};

/// One run of a sweep: a sweep point at one replication (the point holds the
/// scenario, which its replications share).
struct SweepRun {
  size_t index = 0;                  ///< position in plan order
  size_t point = 0;                  ///< which combination of axis values
  uint64_t seed = 0;
  uint64_t replication = 0;
  std::string run_id;                ///< hash of the scenario as run, seed and replication
};

/// Returns a scenario with every default filled in (the runner's resolved
/// scenario); used to accept axis pointers the base file leaves at their default.
using ResolveDefaults = std::function<nlohmann::json(const nlohmann::json& scenario,
                                                     const std::filesystem::path& base_dir)>;

/// A sweep file read and expanded; construction reports every problem as a
/// SweepError naming the sweep file and the JSON pointer inside it.
class SweepPlan {
 public:
  /// Once *stop is set, expanding the points ends with PlanStopped (1e5 points take seconds).
  static SweepPlan load(const std::filesystem::path& sweep_file, const ResolveDefaults& resolve,
                        const std::atomic<bool>* stop = nullptr);
  /// `sweep` is the content of `sweep_file`; a relative base path resolves against its directory.
  static SweepPlan from_json(const nlohmann::json& sweep, const std::filesystem::path& sweep_file,
                             const ResolveDefaults& resolve, const std::atomic<bool>* stop = nullptr);

  const std::vector<SweepAxis>& axes() const { return axes_; }
  const std::vector<SweepRun>& runs() const { return runs_; }
  const std::vector<SweepPoint>& points() const { return points_; }
  /// The scenario a run runs (its point's).
  const nlohmann::json& scenario(const SweepRun& run) const { return points_[run.point].scenario; }
  /// A run's value on an axis.
  const nlohmann::json& value(const SweepRun& run, size_t axis) const {
    return axes_[axis].values[points_[run.point].value_indices[axis]];
  }
  const std::filesystem::path& base_file() const { return base_file_; }
  /// Directory that relative paths inside the base scenario resolve against.
  std::filesystem::path base_dir() const;
  size_t point_count() const { return points_.size(); }
  uint64_t replications() const { return replications_; }
  /// The report's columns the sweep file chose ("figures"; empty: the default).
  const std::vector<std::string>& figures() const { return figures_; }
  /// The sweep file's "keep" key (which runs keep their traces), when it has one.
  const std::optional<KeepPolicy>& keep() const { return keep_; }
  /// "pointer=value, ..." for a run, as error messages show it.
  std::string describe(const SweepRun& run) const;
  /// Where in the sweep file a value of an axis was given ("/axes/1/values/2" or "/axes/1/range").
  std::string value_pointer(size_t axis, size_t value_index) const;
  /// The plan as JSON (axes and every run's id and values), written as plan.json.
  nlohmann::json to_json() const;

 private:
  std::filesystem::path sweep_file_;
  std::filesystem::path base_file_;
  std::vector<SweepAxis> axes_;
  std::vector<SweepPoint> points_;
  std::vector<SweepRun> runs_;
  uint64_t replications_ = 1;
  std::vector<std::string> figures_;
  std::optional<KeepPolicy> keep_;
};

/// A stop request came while the plan was being made: there is no plan, and nothing is wrong with the file.
class PlanStopped : public std::runtime_error {
 public:
  PlanStopped() : std::runtime_error("stopped while planning the sweep") {}
};

/// Bad sweep input: which file, which JSON pointer inside it, and what is wrong.
class SweepError : public std::runtime_error {
 public:
  SweepError(const std::filesystem::path& file, const std::string& pointer, const std::string& message);
  /// Where in the sweep file (empty: the whole file).
  const std::string& pointer() const { return pointer_; }
  const std::string& message() const { return message_; }

 private:
  std::string pointer_;
  std::string message_;
};

/// Expands a {"from", "to", "step"} range into its values, both ends included;
/// integral when from and step are integers. Throws SweepError at `pointer`.
std::vector<nlohmann::json> expand_range(const nlohmann::json& range, const std::filesystem::path& file,
                                         const std::string& pointer);

/// Index tuples of every sweep point, in plan order: cartesian (last axis
/// varies fastest) or zip (the i-th value of every axis).
std::vector<std::vector<size_t>> expand_points(const std::vector<size_t>& axis_sizes, bool zip);

/// The run id: a 64-bit hash (FNV-1a, then the splitmix64 finaliser) of the
/// scenario as run (keys sorted), the seed and the replication, in 16 hex digits.
std::string run_id_of(const nlohmann::json& scenario, uint64_t seed, uint64_t replication);

/// Run ids of one scenario's replications: the scenario is serialised and
/// hashed once, each replication continues from there. Equal to run_id_of.
class RunIds {
 public:
  explicit RunIds(const nlohmann::json& scenario);
  std::string of(uint64_t seed, uint64_t replication) const;

 private:
  uint64_t prefix_hash_;  ///< FNV-1a state after the serialised scenario
};

/// A value as it appears in tables: strings bare, numbers and booleans as JSON.
std::string value_text(const nlohmann::json& value);

}  // namespace latsim::sweep
