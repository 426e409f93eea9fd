#include "latsim/scenario/config.hpp"

#include "latsim/scenario/choice_list.hpp"
#include "latsim/scenario/json_text.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/scenario/schema.hpp"

#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>

namespace latsim::scenario {

using Json = nlohmann::json;

namespace {

std::string located(const std::string& pointer, const std::string& message) {
  return pointer.empty() ? readable(message) : readable_pointer(pointer) + ": " + readable(message);
}

}  // namespace

ScenarioError::ScenarioError(std::string pointer, std::string message, std::filesystem::path file)
    : std::runtime_error(located(pointer, message)),
      pointer_(std::move(pointer)),
      message_(std::move(message)),
      file_(std::move(file)) {}

std::string ScenarioError::line(const std::filesystem::path& named_file) const {
  return readable((file_.empty() ? named_file : file_).string(), kQuotedChars * 2) + ": " + what();
}

std::string join_pointer(std::string_view pointer, std::string_view key) {
  std::string out(pointer);
  out += '/';
  for (char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

ConfigNode::ConfigNode(const Json* node, std::string pointer, std::shared_ptr<ReadLog> log)
    : node_(node), pointer_(std::move(pointer)), log_(std::move(log)) {
  if (!node_->is_object()) throw ScenarioError(pointer_, "expected an object, got " + json_type_name(*node_));
  log_->read_pointers.insert(pointer_);
}

bool ConfigNode::has(std::string_view key) const { return find(key) != nullptr; }

const Json* ConfigNode::find(std::string_view key) const {
  auto it = node_->find(std::string(key));
  return it == node_->end() ? nullptr : &*it;
}

const Json& ConfigNode::require(std::string_view key) const {
  const Json* v = find(key);
  if (!v) fail(key, "required key is missing");
  mark(key);
  return *v;
}

void ConfigNode::mark(std::string_view key) const { log_->read_pointers.insert(join_pointer(pointer_, key)); }

void ConfigNode::record_default(std::string_view key, Json value) const {
  Json::json_pointer p(join_pointer(pointer_, key));
  log_->resolved[p] = std::move(value);
}

void ConfigNode::fail(std::string_view key, const std::string& message) const {
  throw ScenarioError(key.empty() ? pointer_ : join_pointer(pointer_, key), message);
}

ConfigNode ConfigNode::child(std::string_view key) const {
  const Json& v = require(key);
  if (!v.is_object()) fail(key, "expected an object, got " + json_type_name(v));
  return ConfigNode(&v, join_pointer(pointer_, key), log_);
}

std::vector<ConfigNode> ConfigNode::objects(std::string_view key) const {
  const Json& v = require(key);
  if (!v.is_array()) fail(key, "expected an array of objects, got " + json_type_name(v));
  std::vector<ConfigNode> out;
  const std::string base = join_pointer(pointer_, key);
  for (size_t i = 0; i < v.size(); ++i) out.emplace_back(&v[i], join_pointer(base, std::to_string(i)), log_);
  return out;
}

double ConfigNode::as_number(std::string_view key, const Json& v) const {
  if (!v.is_number()) fail(key, "expected a number, got " + json_type_name(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(key, "expected a finite number");
  return x;
}

double ConfigNode::number(std::string_view key) const { return as_number(key, require(key)); }

double ConfigNode::number(std::string_view key, double def) const {
  if (!has(key)) {
    record_default(key, def);
    return def;
  }
  return number(key);
}

double ConfigNode::positive(std::string_view key) const {
  const double x = number(key);
  if (!(x > 0)) fail(key, "must be greater than zero, got " + number_text(x));
  return x;
}

double ConfigNode::positive(std::string_view key, double def) const {
  const double x = number(key, def);
  if (!(x > 0)) fail(key, "must be greater than zero, got " + number_text(x));
  return x;
}

int64_t ConfigNode::integer(std::string_view key, int64_t lo, int64_t hi) const {
  const Json& v = require(key);
  if (!v.is_number_integer() && !(v.is_number_float() && std::floor(v.get<double>()) == v.get<double>() &&
                                  std::fabs(v.get<double>()) < 9e15))
    fail(key, "expected an integer, got " + json_type_name(v));
  const std::string range = "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got ";
  // An unsigned integer past int64's range is out of every range: said as written, not wrapped.
  if (v.is_number_unsigned() && v.get<uint64_t>() > static_cast<uint64_t>(INT64_MAX))
    fail(key, range + integer_text(v.get<uint64_t>()));
  const int64_t x = v.is_number_integer() ? v.get<int64_t>() : static_cast<int64_t>(v.get<double>());
  if (x < lo || x > hi) fail(key, range + integer_text(x));
  return x;
}

int64_t ConfigNode::integer(std::string_view key, int64_t def, int64_t lo, int64_t hi) const {
  if (!has(key)) {
    record_default(key, def);
    return def;
  }
  return integer(key, lo, hi);
}

bool ConfigNode::boolean(std::string_view key, bool def) const {
  if (!has(key)) {
    record_default(key, def);
    return def;
  }
  const Json& v = require(key);
  if (!v.is_boolean()) fail(key, "expected true or false, got " + json_type_name(v));
  return v.get<bool>();
}

std::string ConfigNode::string(std::string_view key) const {
  const Json& v = require(key);
  if (!v.is_string()) fail(key, "expected a string, got " + json_type_name(v));
  // A NUL would cut a file name short where the system reads it: another file, silently.
  if (v.get_ref<const std::string&>().find('\0') != std::string::npos) fail(key, "contains a NUL character (\\u0000)");
  return v.get<std::string>();
}

std::string ConfigNode::string(std::string_view key, std::string def) const {
  if (!has(key)) {
    record_default(key, def);
    return def;
  }
  return string(key);
}

namespace {

void mark_tree(std::set<std::string>& read, const Json& v, const std::string& pointer) {
  read.insert(pointer);
  if (v.is_object()) {
    for (auto it = v.begin(); it != v.end(); ++it) mark_tree(read, it.value(), join_pointer(pointer, it.key()));
  } else if (v.is_array()) {
    for (size_t i = 0; i < v.size(); ++i) mark_tree(read, v[i], join_pointer(pointer, std::to_string(i)));
  }
}

}  // namespace

const Json* ConfigNode::value(std::string_view key) const {
  const Json* v = find(key);
  if (v) mark_tree(log_->read_pointers, *v, join_pointer(pointer_, key));
  return v;
}

std::vector<std::string> ConfigNode::strings(std::string_view key, std::vector<std::string> def) const {
  if (!has(key)) {
    record_default(key, def);
    return def;
  }
  const Json& v = require(key);
  if (!v.is_array()) fail(key, "expected an array of strings, got " + json_type_name(v));
  std::vector<std::string> out;
  for (size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_string())
      throw ScenarioError(join_pointer(join_pointer(pointer_, key), std::to_string(i)),
                          "expected a string, got " + json_type_name(v[i]));
    if (v[i].get_ref<const std::string&>().find('\0') != std::string::npos)
      throw ScenarioError(join_pointer(join_pointer(pointer_, key), std::to_string(i)),
                          "contains a NUL character (\\u0000)");
    out.push_back(v[i].get<std::string>());
  }
  return out;
}

std::string ConfigNode::choice(std::string_view key, std::string def,
                               std::initializer_list<std::string_view> allowed) const {
  const std::string v = string(key, std::move(def));
  for (auto a : allowed)
    if (v == a) return v;
  fail(key, "unknown value " + quote_value(v) + "; expected one of " +
                choice_list(std::vector<std::string>(allowed.begin(), allowed.end())));
}

std::vector<double> ConfigNode::numbers(std::string_view key) const {
  const Json& v = require(key);
  if (!v.is_array()) fail(key, "expected an array of numbers, got " + json_type_name(v));
  std::vector<double> out;
  const std::string base = join_pointer(pointer_, key);
  for (size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
      throw ScenarioError(join_pointer(base, std::to_string(i)), "expected a finite number, got " + json_type_name(v[i]));
    out.push_back(v[i].get<double>());
  }
  return out;
}

std::vector<double> ConfigNode::numbers(std::string_view key, std::vector<double> def) const {
  if (!has(key)) {
    record_default(key, def);
    return def;
  }
  return numbers(key);
}

std::vector<std::vector<double>> ConfigNode::number_rows(std::string_view key) const {
  const Json& v = require(key);
  if (!v.is_array()) fail(key, "expected an array of arrays of numbers, got " + json_type_name(v));
  std::vector<std::vector<double>> out;
  const std::string base = join_pointer(pointer_, key);
  for (size_t i = 0; i < v.size(); ++i) {
    const std::string row_ptr = join_pointer(base, std::to_string(i));
    if (!v[i].is_array()) throw ScenarioError(row_ptr, "expected an array of numbers, got " + json_type_name(v[i]));
    std::vector<double> row;
    for (size_t j = 0; j < v[i].size(); ++j) {
      if (!v[i][j].is_number() || !std::isfinite(v[i][j].get<double>()))
        throw ScenarioError(join_pointer(row_ptr, std::to_string(j)), "expected a finite number");
      row.push_back(v[i][j].get<double>());
    }
    out.push_back(std::move(row));
  }
  return out;
}

des::RationalSeconds ConfigNode::rate_as_period(std::string_view key, std::string def_hz) const {
  Json v;
  if (!has(key)) {
    // Defaults are written as strings so that exact rationals survive.
    v = def_hz.find('/') == std::string::npos ? Json(std::stoll(def_hz)) : Json(def_hz);
    record_default(key, v);
  } else {
    v = require(key);
  }
  if (v.is_number()) {
    const double hz = as_number(key, v);
    if (!(hz > 0)) fail(key, "frequency must be greater than zero, got " + number_text(hz));
    // Represent the decimal exactly enough: micro-hertz resolution.
    const double scaled = std::nearbyint(hz * 1e6);
    if (scaled < 1.0)
      fail(key, "a frequency given as a number must be at least 1e-06 Hz (its resolution), got " + number_text(hz) +
                    "; a slower one as an exact fraction \"num/den\"");
    if (std::fabs(scaled - hz * 1e6) > 1e-3 || scaled > 9e15)
      fail(key, "give frequencies with at most 6 decimals, or as an exact fraction \"num/den\"");
    return des::RationalSeconds::period_of_hz(static_cast<int64_t>(scaled), 1'000'000);
  }
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    const auto slash = s.find('/');
    try {
      size_t used = 0;
      if (slash == std::string::npos) {
        const long long n = std::stoll(s, &used);
        if (used != s.size() || n <= 0) throw std::invalid_argument("bad");
        return des::RationalSeconds::period_of_hz(n, 1);
      }
      const std::string a = s.substr(0, slash), b = s.substr(slash + 1);
      const long long n = std::stoll(a, &used);
      if (used != a.size()) throw std::invalid_argument("bad");
      const long long d = std::stoll(b, &used);
      if (used != b.size() || n <= 0 || d <= 0) throw std::invalid_argument("bad");
      return des::RationalSeconds::period_of_hz(n, d);
    } catch (const std::exception&) {
      fail(key, "expected a frequency in Hz: a number or a positive fraction like \"60000/1001\", got " + quote_value(s));
    }
  }
  fail(key, "expected a frequency in Hz (a number or \"num/den\"), got " + json_type_name(v));
}

des::Time ConfigNode::duration_ms(std::string_view key) const {
  const double ms = number(key);
  if (ms < 0) fail(key, "duration must not be negative, got " + number_text(ms));
  try {
    return des::Time::from_ms(ms);
  } catch (const des::TimeOverflow&) {
    fail(key, "duration out of range");
  }
}

des::Time ConfigNode::duration_ms(std::string_view key, double def_ms) const {
  if (!has(key)) {
    record_default(key, def_ms);
    return des::Time::from_ms(def_ms);
  }
  return duration_ms(key);
}

std::filesystem::path ConfigNode::path(std::string_view key) const {
  std::filesystem::path p = string(key);
  if (p.empty()) fail(key, "empty file path");
  if (p.is_relative()) p = log_->base_dir / p;
  return p.lexically_normal();
}

}  // namespace latsim::scenario
