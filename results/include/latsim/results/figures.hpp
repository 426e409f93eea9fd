// The named figures of a run besides its distributions and counters, its
// warnings, and the one serialisation of all of them into figures JSON.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/stats/stats.hpp"

namespace latsim::results {

class FigureTree;

/// A figure's value: a count, a number, a flag or a word.
using FigureValue = std::variant<int64_t, double, bool, std::string>;

/// Figures by dotted name: "utilisation.gp" nests an object, a numeric part
/// ("memories.0.renders") an array element.
class FigureTable {
 public:
  /// Sets a figure once; a second value for the same name is a logic error.
  void set(const std::string& name, FigureValue value);
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  /// Makes sure an (empty) list or object exists at `name`.
  void list(const std::string& name) { containers_[name] = true; }
  void object(const std::string& name) { containers_[name] = false; }
  /// A distribution kept outside the recorder, serialised like the recorder's.
  void publish(const std::string& name, const stats::Distribution& d);
  void warn(std::string text) { warnings_.push_back(std::move(text)); }
  const std::vector<std::string>& warnings() const { return warnings_; }

  /// The figures object: distributions, then counters under "counts", then
  /// published distributions and named values.
  nlohmann::json to_json(const std::map<std::string, stats::Distribution>& distributions,
                         const std::map<std::string, int64_t>& counters) const;
  /// {count, mean, stddev, min, p50, p90, p99, p999, max, histogram}.
  static nlohmann::json distribution_json(const stats::Distribution& d);

 private:
  friend class FigureTree;  // arranges the same figures without a JSON tree

  std::map<std::string, FigureValue> values_;
  std::map<std::string, bool> containers_;  // name -> true: list, false: object
  std::map<std::string, stats::Distribution> published_;
  std::vector<std::string> warnings_;
};

}  // namespace latsim::results
