// Declaring scenario parameters once. A binding function walks a struct's
// fields through a Section, one call per key, giving its type (by the call),
// default (the field's value on entry), range, unit and meaning:
//
//   void bind(scenario::Section& s, DisplayParams& p) {
//     s.integer("width_px", p.width_px, {.unit = "px", .min = 1, .max = 16384, .doc = "active pixels per line"});
//     s.check("height_px", !(p.interlaced && p.height_px % 2 != 0), "an interlaced display needs an even number of lines");
//   }
//
// The same function serves two modes, like an attribute declaration with its
// checker: reading a scenario object into the struct (every problem a
// ScenarioError naming its JSON pointer, every default applied written into
// the resolved scenario), and describing the object into an ObjectSchema
// (nothing is read and no check runs), from which the JSON Schema and the
// reference documentation are printed.
#pragma once

#include <concepts>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "latsim/des/time.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/scenario/schema.hpp"

namespace latsim::scenario {

/// The check of Section::check_span for a model that learns its item count
/// only when it is built (objects of a generated scene): throws
/// ScenarioError at `pointer` unless per_item_s × items is at most 1e6 s.
void check_span_at(std::string_view pointer, double per_item_s, double items, std::string_view items_text);

/// How a key is declared besides its name, type and default.
struct KeySpec {
  std::string_view unit;          ///< "ms", "Hz", "px", "m", "deg", ...; durations: "s", "ms" or "us"
  std::optional<double> min;      ///< inclusive lower bound (exclusive with above_min)
  std::optional<double> max;      ///< inclusive upper bound
  bool above_min = false;
  int count = 0;                  ///< arrays: exact number of items (0: any); rows: numbers per row
  bool required = false;          ///< no default: the key must be given
  std::string_view doc;           ///< one line of meaning
  std::string_view default_doc;   ///< a default that depends on other keys, in words
};

class Section;

/// One value of a discriminator key: its name, its meaning and the keys it reads.
struct ModeDecl {
  std::string name;
  std::string doc;
  std::function<void(Section&)> bind;
};

/// One JSON object of a scenario, read into structs or described into a schema.
class Section {
 public:
  /// Reading mode: keys come from `node`.
  explicit Section(ConfigNode node);
  /// Describing mode: keys are added to `schema`; nothing is read or checked.
  explicit Section(ObjectSchema& schema);

  bool describing() const { return schema_ != nullptr; }
  /// The JSON pointer of this object (reading mode).
  const std::string& pointer() const;
  /// Whether the scenario gives `key` (always false when describing).
  bool has(std::string_view key) const;
  /// Prose about this object for the reference (describing mode only).
  void doc(std::string_view text);

  void number(std::string_view key, double& v, const KeySpec& spec);
  /// No default: absent stays absent.
  void number(std::string_view key, std::optional<double>& v, const KeySpec& spec);
  template <std::integral I>
  void integer(std::string_view key, I& v, const KeySpec& spec) {
    int64_t x = static_cast<int64_t>(v);
    integer64(key, x, spec, static_cast<int64_t>(std::numeric_limits<I>::min()),
              static_cast<int64_t>(std::numeric_limits<I>::max()));
    v = static_cast<I>(x);
  }
  void flag(std::string_view key, bool& v, const KeySpec& spec);
  void text(std::string_view key, std::string& v, const KeySpec& spec);
  /// One of a fixed set of names, each standing for a value of E.
  template <class E>
  void choice(std::string_view key, E& v, std::initializer_list<std::pair<std::string_view, E>> options,
              const KeySpec& spec) {
    std::vector<std::string> names;
    std::string current;
    for (const auto& [name, value] : options) {
      names.emplace_back(name);
      if (value == v) current = name;
    }
    const std::string chosen = choice_name(key, current, names, spec);
    for (const auto& [name, value] : options)
      if (name == chosen) v = value;
  }
  /// A list of names, each one of `names` (absent: `v` as it is).
  void choices(std::string_view key, std::vector<std::string>& v, const std::vector<std::string>& names,
               const KeySpec& spec);
  /// A frequency in Hz, a number (60) or an exact fraction ("60000/1001"), kept as its exact period.
  void rate(std::string_view key, des::RationalSeconds& period, const KeySpec& spec);
  /// A duration in spec.unit ("s", "ms" or "us"), not negative unless spec.min says otherwise.
  void duration(std::string_view key, des::Time& v, const KeySpec& spec);
  /// No default: absent stays absent (spec.default_doc says what happens then).
  void duration(std::string_view key, std::optional<des::Time>& v, const KeySpec& spec);
  void numbers(std::string_view key, std::vector<double>& v, const KeySpec& spec);
  /// Rows of numbers (points, a matrix); spec.count is the length of each row.
  void number_rows(std::string_view key, std::vector<std::vector<double>>& v, const KeySpec& spec);
  void number_rows(std::string_view key, std::optional<std::vector<std::vector<double>>>& v, const KeySpec& spec);
  /// A file name; relative names are taken from the scenario file's directory.
  void path(std::string_view key, std::filesystem::path& v, const KeySpec& spec);
  /// Any JSON value, kept as given (absent: `v` as it is), for values that are
  /// themselves scenario content: a sweep's axis values and overrides.
  void value(std::string_view key, nlohmann::json& v, const KeySpec& spec);

  /// A nested object; when absent (and not required) its keys take their
  /// defaults, which are written into the resolved scenario.
  template <class T, class F>
  void object(std::string_view key, T& v, F&& bind, const KeySpec& spec) {
    nested(key, "object", spec, [&](Section& s) { bind(s, v); });
  }
  /// A nested object whose absence means "none" (nothing is recorded then).
  template <class T, class F>
  void optional_object(std::string_view key, std::optional<T>& v, F&& bind, const KeySpec& spec) {
    if (describing()) {
      T dummy{};
      nested(key, "object", spec, [&](Section& s) { bind(s, dummy); });
      return;
    }
    if (!has(key)) return;
    T value{};
    nested(key, "object", spec, [&](Section& s) { bind(s, value); });
    v = std::move(value);
  }
  /// An array of objects (absent: empty).
  template <class T, class F>
  void objects(std::string_view key, std::vector<T>& v, F&& bind, const KeySpec& spec) {
    if (describing()) {
      T dummy{};
      nested(key, "objects", spec, [&](Section& s) { bind(s, dummy); });
      return;
    }
    v.clear();
    for (ConfigNode& node : array_of_objects(key)) {
      T value{};
      Section s(std::move(node));
      bind(s, value);
      v.push_back(std::move(value));
    }
  }
  /// A discriminator: reads `key` (default `default_mode`; empty: required)
  /// and binds the keys of the selected mode only. Described, every mode's
  /// keys are listed with the modes that read them.
  std::string modes(std::string_view key, std::string_view default_mode, const std::vector<ModeDecl>& modes,
                    const KeySpec& spec);

  /// A cross-field rule: fails at `key` with `message` unless `ok`.
  void check(std::string_view key, bool ok, std::string_view message);
  /// The same for a key elsewhere in the scenario, by its absolute JSON pointer.
  void check_pointer(std::string_view pointer, bool ok, std::string_view message);
  /// Documents a rule at `key` that is checked elsewhere, item by item and
  /// with each item's own pointer (check_pointer): the rule appears in the
  /// schema and the reference; reading does nothing here.
  void rule(std::string_view key, std::string_view message) {
    if (describing()) check(key, true, message);
  }
  /// A cross-field rule on time: `per_item_s` (what the value of `key` costs) times
  /// `items` (described by `items_text`, such as "/scene/triangles × 2 eyes")
  /// must not exceed the longest span a scenario may imply, 1e6 s, so that
  /// the run can add it to its clock.
  void check_span(std::string_view key, double per_item_s, double items, std::string_view items_text);
  /// Runs fn (reading mode only); a std::exception it throws becomes an error at `key`.
  void guard(std::string_view key, const std::function<void()>& fn);
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;

 private:
  void integer64(std::string_view key, int64_t& v, const KeySpec& spec, int64_t type_min, int64_t type_max);
  std::string choice_name(std::string_view key, const std::string& current, const std::vector<std::string>& names,
                          const KeySpec& spec);
  void nested(std::string_view key, const char* type, const KeySpec& spec, const std::function<void(Section&)>& bind);
  std::vector<ConfigNode> array_of_objects(std::string_view key) const;
  KeySchema& declare(std::string_view key, const char* type, const KeySpec& spec);
  void check_range(std::string_view key, double x, const KeySpec& spec) const;
  void add_rule(std::string text);

  std::optional<ConfigNode> node_;
  ObjectSchema* schema_ = nullptr;
  std::string mode_;  // describing: the mode whose keys are being declared
};

}  // namespace latsim::scenario
