// What a scenario may contain, as declared by the parameter bindings: every
// object, its keys with type, default, range, unit and meaning, its modes and
// its cross-field rules. Printed as JSON Schema and as Markdown.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace latsim::scenario {

struct ObjectSchema;

/// One declared key of an object.
struct KeySchema {
  /// number, integer, boolean, string, choice, choices, rate, duration, path, numbers,
  /// number_rows, object, objects.
  std::string name;
  std::string type;
  nlohmann::json default_value;  ///< null: no default (required, or absent means "none")
  std::string default_doc;       ///< a default given in words (it depends on other keys)
  bool required = false;
  std::optional<double> min, max;
  bool above_min = false;        ///< min is exclusive
  int count = 0;                 ///< arrays: exact number of items (0: any)
  int row_count = 0;             ///< number_rows: exact numbers per row (0: any)
  std::vector<std::string> choices;
  std::string unit;
  std::string doc;
  /// When it is read: each entry a condition such as "type=serial, host=poll"
  /// (empty: always).
  std::vector<std::string> modes;
  std::shared_ptr<ObjectSchema> object;   ///< object and objects: what the object holds
};

/// One JSON object of a scenario.
struct ObjectSchema {
  std::string doc;                ///< prose for the reference
  /// Keys whose value selects which other keys are read ("type"), with each value's meaning.
  struct Discriminator {
    std::string key;
    std::vector<std::pair<std::string, std::string>> values;
  };
  std::vector<Discriminator> discriminators;
  std::vector<KeySchema> keys;
  /// Cross-field checks in words, each with the mode that makes it (empty: always).
  std::vector<std::pair<std::string, std::string>> rules;

  const KeySchema* find(std::string_view key) const;
  /// The schema of the value at a JSON pointer below this object (nullptr: not declared).
  const KeySchema* key_at(std::string_view pointer) const;
};

/// The JSON Schema (draft 7) of a scenario file.
nlohmann::json json_schema(const ObjectSchema& root);
/// The scenario reference in Markdown.
std::string markdown_reference(const ObjectSchema& root);

}  // namespace latsim::scenario
