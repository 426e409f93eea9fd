// Reading JSON that a user hands latsim (scenario, include and sweep files,
// --set values): bounded in size and nesting, duplicate keys refused, and
// every problem a ScenarioError that says where (line, column and the JSON
// pointer of the value being read) in one readable line.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace latsim::scenario {

/// How much JSON latsim accepts from one file or value.
struct JsonLimits {
  /// Scenario and sweep files are a few kilobytes; 16 MiB leaves room for
  /// long walk paths and probe lists while refusing a runaway file at once.
  size_t max_bytes = size_t{16} << 20;
  /// Scenarios nest five or six levels deep; anything near this is not a scenario.
  int max_depth = 64;
};

/// Reads a whole regular file of at most `max_bytes`. Throws ScenarioError
/// (empty pointer, file() = `file`) saying what is wrong with the `what`
/// ("scenario file", "sweep file"): missing, a directory or device,
/// unreadable, too large.
std::string read_text_file(const std::filesystem::path& file, std::string_view what, size_t max_bytes);

/// Parses `text` read from `source` within `limits`. Throws ScenarioError
/// (file() = `source`) at the JSON pointer of the offending value, with line
/// and column, for malformed JSON, a number too large for a double, nesting
/// deeper than the limit, or a key given twice in one object.
nlohmann::json parse_json(std::string_view text, const std::string& source, const JsonLimits& limits = {});

/// The same for a command-line value: nothing when `text` is not JSON at all
/// (a bare word, which the caller may take as a string), the value when it
/// is, and ScenarioError when it is JSON beyond a limit (a number out of
/// range, a repeated key, too deep).
std::optional<nlohmann::json> parse_json_value(std::string_view text, const std::string& source,
                                               const JsonLimits& limits = {});

/// What a value is, for a message: "a number", "a string", "a boolean",
/// "an array", "an object" or "null".
std::string json_type_name(const nlohmann::json& v);

/// read_text_file, then parse_json.
nlohmann::json read_json_file(const std::filesystem::path& file, std::string_view what, const JsonLimits& limits = {});

}  // namespace latsim::scenario
