// The values of keys a scenario gives but its chosen modes do not read: each
// is still checked against its declaration (type, range, choices, nested
// keys), through the same Section calls that read it, on a copy that records
// nothing and loads no file. A key several modes declare differently is
// accepted when it fits any one of its declarations.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "latsim/scenario/choice_list.hpp"
#include "latsim/scenario/json_text.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/scenario/section.hpp"
#include "section_internal.hpp"

namespace latsim::scenario {

namespace {

using Json = nlohmann::json;

KeySpec spec_of(const KeySchema& k) {
  KeySpec s;
  s.unit = k.unit;
  s.min = k.min;
  s.max = k.max;
  s.above_min = k.above_min;
  s.count = k.type == "number_rows" ? k.row_count : k.count;
  s.required = true;  // it is given: read it as a value that must be there
  return s;
}

void check_object(const ObjectSchema& schema, const Json& object, const std::string& pointer);

// Throws ScenarioError at pointer/name when `value` does not fit `k`.
void check_against(const KeySchema& k, const Json& value, const std::string& parent, const std::string& pointer) {
  if (k.type == "object") {
    if (!value.is_object()) throw ScenarioError(pointer, "expected an object, got " + json_type_name(value));
    if (k.object) check_object(*k.object, value, pointer);
    return;
  }
  if (k.type == "objects") {
    if (!value.is_array()) throw ScenarioError(pointer, "expected an array of objects, got " + json_type_name(value));
    for (size_t i = 0; i < value.size(); ++i) {
      const std::string at = join_pointer(pointer, std::to_string(i));
      if (!value[i].is_object()) throw ScenarioError(at, "expected an object, got " + json_type_name(value[i]));
      if (k.object) check_object(*k.object, value[i], at);
    }
    return;
  }
  // A one-key copy read through the declaration's own Section call: the same
  // messages as a read, and nothing recorded in the scenario's read log.
  const Json holder = Json::object({{k.name, value}});
  auto log = std::make_shared<ReadLog>();
  Section s(ConfigNode(&holder, parent, log));
  const KeySpec spec = spec_of(k);
  if (k.type == "number") {
    double v = 0.0;
    s.number(k.name, v, spec);
  } else if (k.type == "integer") {
    int64_t v = 0;
    s.integer(k.name, v, spec);
  } else if (k.type == "boolean") {
    bool v = false;
    s.flag(k.name, v, spec);
  } else if (k.type == "string" || k.type == "path") {
    std::string v;
    s.text(k.name, v, spec);  // a path is only a name here: no file is looked at
  } else if (k.type == "choices") {
    std::vector<std::string> v;
    s.choices(k.name, v, k.choices, spec);
  } else if (k.type == "choice") {
    std::string v;
    s.text(k.name, v, spec);
    if (std::find(k.choices.begin(), k.choices.end(), v) != k.choices.end()) return;
    throw ScenarioError(pointer, "unknown value " + quote_value(v) + "; expected one of " + choice_list(k.choices));
  } else if (k.type == "rate") {
    des::RationalSeconds period{1, 1};
    s.rate(k.name, period, spec);
  } else if (k.type == "duration") {
    des::Time v;
    s.duration(k.name, v, spec);
  } else if (k.type == "numbers") {
    std::vector<double> v;
    s.numbers(k.name, v, spec);
  } else if (k.type == "number_rows") {
    std::vector<std::vector<double>> v;
    s.number_rows(k.name, v, spec);
  }
}

// Every key of an unread object, against the declarations of its place.
void check_object(const ObjectSchema& schema, const Json& object, const std::string& pointer) {
  for (auto it = object.begin(); it != object.end(); ++it)
    check_unread_value(schema, it.key(), it.value(), pointer);
}

}  // namespace

void check_unread_value(const ObjectSchema& parent_schema, const std::string& name, const Json& value,
                        const std::string& parent) {
  const std::string pointer = join_pointer(parent, name);
  std::optional<ScenarioError> first;
  bool declared = false;
  for (const KeySchema& k : parent_schema.keys) {
    if (k.name != name) continue;
    declared = true;
    try {
      check_against(k, value, parent, pointer);
      return;
    } catch (const ScenarioError& e) {
      if (!first) first = e;
    }
  }
  if (!declared) throw ScenarioError(pointer, "unknown key (check its spelling, or remove it: nothing reads it)");
  throw *first;
}

}  // namespace latsim::scenario
