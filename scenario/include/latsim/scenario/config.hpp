// Reading scenario files: JSON with includes and overrides, read through
// ConfigNode views that report every problem with its JSON pointer.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/des/time.hpp"

namespace latsim::scenario {

struct ObjectSchema;

/// Bad scenario input: names the JSON pointer of the problem and, when it is
/// not the file the user named (an included file), the file it is in.
/// what() is "pointer: message" (just the message for the whole document),
/// cut to a readable length on one line.
class ScenarioError : public std::runtime_error {
 public:
  ScenarioError(std::string pointer, std::string message, std::filesystem::path file = {});
  const std::string& pointer() const { return pointer_; }
  const std::string& message() const { return message_; }
  const std::filesystem::path& file() const { return file_; }
  /// The one line to print: "<file>: <pointer>: <message>", the file being
  /// file() when set and `named_file` (what the user gave) otherwise.
  std::string line(const std::filesystem::path& named_file) const;

 private:
  std::string pointer_;
  std::string message_;
  std::filesystem::path file_;
};

/// Appends an escaped key to a JSON pointer ("/a" + "b/c" -> "/a/b~1c").
std::string join_pointer(std::string_view pointer, std::string_view key);

/// Shared bookkeeping of one loaded scenario: which keys were read, and the
/// scenario as resolved (input plus every default that was applied).
struct ReadLog {
  std::set<std::string> read_pointers;
  nlohmann::json resolved;
  std::filesystem::path base_dir;
};

/// A read-only view of one JSON object in a scenario that records every key it
/// reads (unread keys are reported as unknown) and every default it applies.
class ConfigNode {
 public:
  ConfigNode(const nlohmann::json* node, std::string pointer, std::shared_ptr<ReadLog> log);

  const std::string& pointer() const { return pointer_; }
  bool has(std::string_view key) const;

  ConfigNode child(std::string_view key) const;
  std::vector<ConfigNode> objects(std::string_view key) const;

  double number(std::string_view key) const;
  double number(std::string_view key, double def) const;
  double positive(std::string_view key) const;
  double positive(std::string_view key, double def) const;
  int64_t integer(std::string_view key, int64_t lo, int64_t hi) const;
  int64_t integer(std::string_view key, int64_t def, int64_t lo, int64_t hi) const;
  bool boolean(std::string_view key, bool def) const;
  std::string string(std::string_view key) const;
  std::string string(std::string_view key, std::string def) const;
  std::string choice(std::string_view key, std::string def,
                     std::initializer_list<std::string_view> allowed) const;
  std::vector<double> numbers(std::string_view key) const;
  std::vector<double> numbers(std::string_view key, std::vector<double> def) const;
  std::vector<std::vector<double>> number_rows(std::string_view key) const;
  /// An array of strings (absent: `def`).
  std::vector<std::string> strings(std::string_view key, std::vector<std::string> def) const;
  /// A frequency in Hz, a number (60) or an exact string ("60000/1001"), as its exact period.
  des::RationalSeconds rate_as_period(std::string_view key, std::string def_hz) const;
  des::Time duration_ms(std::string_view key) const;
  des::Time duration_ms(std::string_view key, double def_ms) const;
  /// A file path, relative paths resolved against the scenario file's directory.
  std::filesystem::path path(std::string_view key) const;
  /// Any JSON value, as given: it and everything inside it count as read
  /// (a value a sweep puts into a scenario). Nothing when absent.
  const nlohmann::json* value(std::string_view key) const;

  [[noreturn]] void fail(std::string_view key, const std::string& message) const;
  const std::shared_ptr<ReadLog>& log() const { return log_; }
  /// Raw access; marks nothing as read.
  const nlohmann::json& json() const { return *node_; }

 private:
  const nlohmann::json* find(std::string_view key) const;
  const nlohmann::json& require(std::string_view key) const;
  void mark(std::string_view key) const;
  void record_default(std::string_view key, nlohmann::json value) const;
  double as_number(std::string_view key, const nlohmann::json& v) const;

  const nlohmann::json* node_;
  std::string pointer_;
  std::shared_ptr<ReadLog> log_;
};

/// A scenario file loaded with its includes and overrides applied.
class ScenarioDocument {
 public:
  /// Loads `file`; `overrides` are "/json/pointer=value" strings (value parsed
  /// as JSON, or taken as a string when it is not valid JSON). With a schema,
  /// an override may create an object the schema declares (an optional
  /// section the scenario left out).
  static ScenarioDocument load(const std::filesystem::path& file, const std::vector<std::string>& overrides = {},
                               const ObjectSchema* schema = nullptr);
  /// The same for a scenario given as JSON text rather than a file (a program
  /// builds it in memory): `name` stands for the file in every message, and
  /// its directory is where included and data files are looked for.
  static ScenarioDocument parse(std::string_view text, const std::filesystem::path& name,
                                const std::vector<std::string>& overrides = {}, const ObjectSchema* schema = nullptr);
  static ScenarioDocument from_json(nlohmann::json doc, std::filesystem::path base_dir);

  ConfigNode root() const;
  const nlohmann::json& json() const { return doc_; }
  /// Throws ScenarioError naming the first key (in document order) nobody
  /// read. A key `schema` declares for its place (read in another mode of
  /// its object) is not an error: it gets a line in `warnings` instead.
  void check_unknown_keys(const ObjectSchema* schema = nullptr, std::vector<std::string>* warnings = nullptr) const;
  /// The scenario as read: input plus every default applied (a run adds
  /// the clock phases it drew: run::PreparedRun::resolved()).
  const nlohmann::json& resolved() const { return log_->resolved; }

 private:
  nlohmann::json doc_;
  std::shared_ptr<ReadLog> log_;
};

/// Applies one "/pointer=value" override to a document. A missing parent is
/// an error, unless `schema` declares it as an object: then it is made.
void apply_override(nlohmann::json& doc, const std::string& assignment, const ObjectSchema* schema = nullptr);

}  // namespace latsim::scenario
