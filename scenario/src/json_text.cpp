#include "latsim/scenario/json_text.hpp"

#include <vector>

#include "latsim/io/input_file.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/scenario/readable.hpp"

namespace latsim::scenario {

using Json = nlohmann::json;

namespace {

// "line 3, column 7" of a byte offset (both counted from 1).
std::string line_and_column(std::string_view text, size_t offset) {
  offset = std::min(offset, text.size());
  size_t line = 1, line_start = 0;
  for (size_t i = 0; i < offset; ++i)
    if (text[i] == '\n') ++line, line_start = i + 1;
  return "line " + std::to_string(line) + ", column " + std::to_string(offset - line_start + 1);
}

// The part of a library message that speaks to the user: nlohmann's
// "[json.exception.parse_error.101] parse error at line 1, column 2: syntax
// error while parsing value - invalid literal; last read: 'x'" becomes
// "syntax error while parsing value - invalid literal; last read: 'x'".
std::string library_reason(const nlohmann::detail::exception& ex, const std::string& last_token) {
  if (ex.id == 406) return "number out of range: " + readable(last_token, kQuotedChars);
  std::string what = ex.what();
  if (const auto column = what.find(", column "); column != std::string::npos) {
    if (const auto colon = what.find(": ", column); colon != std::string::npos) what = what.substr(colon + 2);
  } else if (const auto bracket = what.find("] "); bracket != std::string::npos) {
    what = what.substr(bracket + 2);
  }
  // The "last read" token may be anything the user wrote, of any length.
  if (const auto last = what.find("; last read: '"); last != std::string::npos)
    what = what.substr(0, last) + "; last read: " + quote_value(last_token);
  return what;
}

/// Builds the document like nlohmann's own DOM parser, refusing what it
/// would accept silently: nesting beyond the limit and repeated keys.
class CheckedDomBuilder {
 public:
  CheckedDomBuilder(std::string_view text, int max_depth) : text_(text), max_depth_(max_depth) {}

  bool null() { return add(Json(nullptr)); }
  bool boolean(bool v) { return add(Json(v)); }
  bool number_integer(Json::number_integer_t v) { return add(Json(v)); }
  bool number_unsigned(Json::number_unsigned_t v) { return add(Json(v)); }
  bool number_float(Json::number_float_t v, const std::string&) { return add(Json(v)); }
  bool string(std::string& v) { return add(Json(std::move(v))); }
  bool binary(Json::binary_t& v) { return add(Json::binary(std::move(v))); }
  bool start_object(size_t) { return open(Json::object()); }
  bool start_array(size_t) { return open(Json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(std::string& k) {
    Level& level = levels_.back();
    if (level.node->contains(k)) {
      error_ = ScenarioError(join_pointer(pointer_above(levels_.size() - 1), k),
                             "key given twice in one object (JSON would keep only the last)");
      return false;
    }
    level.key = k;
    level.slot = &(*level.node)[k];
    return true;
  }

  bool parse_error(size_t position, const std::string& last_token, const nlohmann::detail::exception& ex) {
    syntax_ = ex.id == 101;
    error_ = ScenarioError(pointer_above(levels_.size()), "malformed JSON at " +
                                                           line_and_column(text_, position ? position - 1 : 0) + ": " +
                                                           library_reason(ex, last_token));
    return false;
  }

  Json take() { return std::move(root_); }
  const std::optional<ScenarioError>& error() const { return error_; }
  /// The text is not JSON at all (as opposed to JSON beyond a limit).
  bool syntax_error() const { return syntax_; }

 private:
  // One open object or array: the value being filled and, in an object, the
  // key whose value comes next.
  struct Level {
    Json* node;
    std::optional<std::string> key;
    Json* slot = nullptr;
  };

  // The pointer of the value being read inside the first `depth` open levels.
  std::string pointer_above(size_t depth) const {
    std::string p;
    for (size_t i = 0; i < depth && i < levels_.size(); ++i) {
      // An array with an open child is reading its last entry; the innermost one its next.
      const size_t size = levels_[i].node->size();
      const bool open_child = i + 1 < levels_.size();
      if (levels_[i].node->is_array()) p = join_pointer(p, std::to_string(open_child ? size - 1 : size));
      else if (levels_[i].key) p = join_pointer(p, *levels_[i].key);
    }
    return p;
  }

  Json* place(Json value) {
    if (levels_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    Level& level = levels_.back();
    if (level.node->is_array()) {
      level.node->push_back(std::move(value));
      return &level.node->back();
    }
    *level.slot = std::move(value);
    return level.slot;
  }

  bool add(Json value) {
    place(std::move(value));
    return true;
  }

  bool open(Json container) {
    if (static_cast<int>(levels_.size()) >= max_depth_) {
      error_ = ScenarioError(pointer_above(levels_.size()),
                             "nested more than " + std::to_string(max_depth_) + " levels deep (no scenario needs that)");
      return false;
    }
    levels_.push_back(Level{place(std::move(container)), std::nullopt, nullptr});
    return true;
  }

  bool close() {
    levels_.pop_back();
    return true;
  }

  std::string_view text_;
  int max_depth_;
  Json root_;
  std::vector<Level> levels_;
  std::optional<ScenarioError> error_;
  bool syntax_ = false;
};

// Parses with the checks; the builder holds the outcome.
void run_parser(std::string_view text, const std::string& source, const JsonLimits& limits, CheckedDomBuilder& builder) {
  if (text.size() > limits.max_bytes)
    throw ScenarioError("", "too large (" + std::to_string(text.size()) + " bytes; at most " +
                                std::to_string(limits.max_bytes) + ")", source);
  const bool ok = Json::sax_parse(text.begin(), text.end(), &builder);
  if (!ok && !builder.error()) throw ScenarioError("", "malformed JSON", source);
}

}  // namespace

std::string read_text_file(const std::filesystem::path& file, std::string_view what, size_t max_bytes) {
  try {
    return io::read_input_file(file, max_bytes);
  } catch (const io::InputFileError& e) {
    throw ScenarioError("", "cannot read the " + std::string(what) + ": " + e.what(), file);
  }
}

Json parse_json(std::string_view text, const std::string& source, const JsonLimits& limits) {
  CheckedDomBuilder builder(text, limits.max_depth);
  run_parser(text, source, limits, builder);
  if (const auto& e = builder.error()) throw ScenarioError(e->pointer(), e->message(), source);
  return builder.take();
}

std::optional<Json> parse_json_value(std::string_view text, const std::string& source, const JsonLimits& limits) {
  CheckedDomBuilder builder(text, limits.max_depth);
  run_parser(text, source, limits, builder);
  if (builder.syntax_error()) return std::nullopt;
  if (const auto& e = builder.error()) throw ScenarioError(e->pointer(), e->message(), source);
  return builder.take();
}

std::string json_type_name(const Json& v) {
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_boolean()) return "a boolean";
  if (v.is_array()) return "an array";
  if (v.is_object()) return "an object";
  return "null";
}

Json read_json_file(const std::filesystem::path& file, std::string_view what, const JsonLimits& limits) {
  return parse_json(read_text_file(file, what, limits.max_bytes), file.string(), limits);
}

}  // namespace latsim::scenario
