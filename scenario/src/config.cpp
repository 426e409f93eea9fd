#include "latsim/scenario/config.hpp"

#include "latsim/scenario/schema.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace latsim::scenario {

using Json = nlohmann::json;

ScenarioError::ScenarioError(std::string pointer, std::string message)
    : std::runtime_error((pointer.empty() ? std::string("/") : pointer) + ": " + message),
      pointer_(std::move(pointer)),
      message_(std::move(message)) {}

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

namespace {

std::string type_name(const Json& v) {
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_boolean()) return "a boolean";
  if (v.is_array()) return "an array";
  if (v.is_object()) return "an object";
  return "null";
}

std::string format_number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

}  // namespace

ConfigNode::ConfigNode(const Json* node, std::string pointer, std::shared_ptr<ReadLog> log)
    : node_(node), pointer_(std::move(pointer)), log_(std::move(log)) {
  if (!node_->is_object()) throw ScenarioError(pointer_, "expected an object, got " + type_name(*node_));
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

void ConfigNode::mark_all_read() const {
  std::vector<std::pair<const Json*, std::string>> stack{{node_, pointer_}};
  while (!stack.empty()) {
    auto [n, p] = stack.back();
    stack.pop_back();
    log_->read_pointers.insert(p);
    if (n->is_object())
      for (auto it = n->begin(); it != n->end(); ++it) stack.emplace_back(&*it, join_pointer(p, it.key()));
    else if (n->is_array())
      for (size_t i = 0; i < n->size(); ++i) stack.emplace_back(&(*n)[i], join_pointer(p, std::to_string(i)));
  }
}

ConfigNode ConfigNode::child(std::string_view key) const {
  const Json& v = require(key);
  if (!v.is_object()) fail(key, "expected an object, got " + type_name(v));
  return ConfigNode(&v, join_pointer(pointer_, key), log_);
}

std::optional<ConfigNode> ConfigNode::optional_child(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return child(key);
}

std::vector<ConfigNode> ConfigNode::objects(std::string_view key) const {
  const Json& v = require(key);
  if (!v.is_array()) fail(key, "expected an array of objects, got " + type_name(v));
  std::vector<ConfigNode> out;
  const std::string base = join_pointer(pointer_, key);
  for (size_t i = 0; i < v.size(); ++i) out.emplace_back(&v[i], join_pointer(base, std::to_string(i)), log_);
  return out;
}

double ConfigNode::as_number(std::string_view key, const Json& v) const {
  if (!v.is_number()) fail(key, "expected a number, got " + type_name(v));
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
  if (!(x > 0)) fail(key, "must be greater than zero, got " + format_number(x));
  return x;
}

double ConfigNode::positive(std::string_view key, double def) const {
  const double x = number(key, def);
  if (!(x > 0)) fail(key, "must be greater than zero, got " + format_number(x));
  return x;
}

double ConfigNode::non_negative(std::string_view key, double def) const {
  const double x = number(key, def);
  if (x < 0) fail(key, "must not be negative, got " + format_number(x));
  return x;
}

double ConfigNode::number_in(std::string_view key, double def, double lo, double hi) const {
  const double x = number(key, def);
  if (x < lo || x > hi)
    fail(key, "must lie in [" + format_number(lo) + ", " + format_number(hi) + "], got " + format_number(x));
  return x;
}

int64_t ConfigNode::integer(std::string_view key, int64_t lo, int64_t hi) const {
  const Json& v = require(key);
  if (!v.is_number_integer() && !(v.is_number_float() && std::floor(v.get<double>()) == v.get<double>() &&
                                  std::fabs(v.get<double>()) < 9e15))
    fail(key, "expected an integer, got " + type_name(v));
  const int64_t x = v.is_number_integer() ? v.get<int64_t>() : static_cast<int64_t>(v.get<double>());
  if (x < lo || x > hi)
    fail(key, "must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(x));
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
  if (!v.is_boolean()) fail(key, "expected true or false, got " + type_name(v));
  return v.get<bool>();
}

std::string ConfigNode::string(std::string_view key) const {
  const Json& v = require(key);
  if (!v.is_string()) fail(key, "expected a string, got " + type_name(v));
  return v.get<std::string>();
}

std::string ConfigNode::string(std::string_view key, std::string def) const {
  if (!has(key)) {
    record_default(key, def);
    return def;
  }
  return string(key);
}

std::vector<std::string> ConfigNode::strings(std::string_view key, std::vector<std::string> def) const {
  if (!has(key)) {
    record_default(key, def);
    return def;
  }
  const Json& v = require(key);
  if (!v.is_array()) fail(key, "expected an array of strings, got " + type_name(v));
  std::vector<std::string> out;
  for (size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_string())
      throw ScenarioError(join_pointer(join_pointer(pointer_, key), std::to_string(i)),
                          "expected a string, got " + type_name(v[i]));
    out.push_back(v[i].get<std::string>());
  }
  return out;
}

std::string ConfigNode::choice(std::string_view key, std::string def,
                               std::initializer_list<std::string_view> allowed) const {
  const std::string v = string(key, std::move(def));
  for (auto a : allowed)
    if (v == a) return v;
  std::string list;
  for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string("\"") + std::string(a) + "\"";
  fail(key, "unknown value \"" + v + "\"; expected one of " + list);
}

std::vector<double> ConfigNode::numbers(std::string_view key) const {
  const Json& v = require(key);
  if (!v.is_array()) fail(key, "expected an array of numbers, got " + type_name(v));
  std::vector<double> out;
  const std::string base = join_pointer(pointer_, key);
  for (size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
      throw ScenarioError(join_pointer(base, std::to_string(i)), "expected a finite number, got " + type_name(v[i]));
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
  if (!v.is_array()) fail(key, "expected an array of arrays of numbers, got " + type_name(v));
  std::vector<std::vector<double>> out;
  const std::string base = join_pointer(pointer_, key);
  for (size_t i = 0; i < v.size(); ++i) {
    const std::string row_ptr = join_pointer(base, std::to_string(i));
    if (!v[i].is_array()) throw ScenarioError(row_ptr, "expected an array of numbers, got " + type_name(v[i]));
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
    if (!(hz > 0)) fail(key, "frequency must be greater than zero, got " + format_number(hz));
    // Represent the decimal exactly enough: micro-hertz resolution.
    const double scaled = std::nearbyint(hz * 1e6);
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
      fail(key, "expected a frequency in Hz: a number or a positive fraction like \"60000/1001\", got \"" + s + "\"");
    }
  }
  fail(key, "expected a frequency in Hz (a number or \"num/den\"), got " + type_name(v));
}

des::Time ConfigNode::duration_ms(std::string_view key) const {
  const double ms = number(key);
  if (ms < 0) fail(key, "duration must not be negative, got " + format_number(ms));
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

// ---------------------------------------------------------------------------

namespace {

Json parse_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ScenarioError("", "cannot open scenario file " + file.string());
  std::ostringstream buf;
  buf << in.rdbuf();
  const std::string text = buf.str();
  try {
    return Json::parse(text);
  } catch (const Json::parse_error& e) {
    // Turn the byte offset into a line number for the user.
    size_t line = 1;
    for (size_t i = 0; i < e.byte && i < text.size(); ++i)
      if (text[i] == '\n') ++line;
    std::string what = e.what();
    const auto pos = what.find("; ");
    throw ScenarioError("", "malformed JSON in " + file.string() + " at line " + std::to_string(line) + ": " +
                                (pos == std::string::npos ? what : what.substr(pos + 2)));
  }
}

// Objects merge key by key; anything else in `over` replaces `base`. An
// object whose "type" differs from the base's is a different thing altogether
// (a trace instead of a sinusoid) and replaces it whole.
void deep_merge(Json& base, const Json& over) {
  const bool retyped = base.is_object() && over.is_object() && base.contains("type") && over.contains("type") &&
                       base["type"] != over["type"];
  if (!base.is_object() || !over.is_object() || retyped) {
    base = over;
    return;
  }
  for (auto it = over.begin(); it != over.end(); ++it) {
    if (base.contains(it.key())) deep_merge(base[it.key()], it.value());
    else base[it.key()] = it.value();
  }
}

Json load_with_includes(const std::filesystem::path& file, std::vector<std::filesystem::path>& chain) {
  const auto canon = std::filesystem::weakly_canonical(file);
  for (const auto& c : chain)
    if (c == canon) throw ScenarioError("/include", "include cycle through " + file.string());
  chain.push_back(canon);
  Json doc = parse_file(file);
  if (!doc.is_object()) throw ScenarioError("", "a scenario must be a JSON object");
  Json result = Json::object();
  if (doc.contains("include")) {
    const Json inc = doc["include"];
    std::vector<std::string> files;
    if (inc.is_string()) files.push_back(inc.get<std::string>());
    else if (inc.is_array()) {
      for (size_t i = 0; i < inc.size(); ++i) {
        if (!inc[i].is_string()) throw ScenarioError("/include/" + std::to_string(i), "expected a file name");
        files.push_back(inc[i].get<std::string>());
      }
    } else {
      throw ScenarioError("/include", "expected a file name or an array of file names");
    }
    for (const auto& f : files) {
      std::filesystem::path p = f;
      if (p.is_relative()) p = file.parent_path() / p;
      if (!std::filesystem::exists(p)) throw ScenarioError("/include", "included file not found: " + p.string());
      deep_merge(result, load_with_includes(p, chain));
    }
    doc.erase("include");
  }
  deep_merge(result, doc);
  chain.pop_back();
  return result;
}

}  // namespace

void apply_override(Json& doc, const std::string& assignment, const ObjectSchema* schema) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || assignment.empty() || assignment[0] != '/')
    throw ScenarioError("", "override \"" + assignment + "\" must look like /json/pointer=value");
  const std::string ptr = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  Json value;
  try {
    value = Json::parse(text);
  } catch (const Json::parse_error&) {
    value = text;  // a bare word is a string
  }
  try {
    Json::json_pointer p(ptr);
    if (!p.parent_pointer().empty() && !doc.contains(p.parent_pointer())) {
      // Every missing ancestor must be an object the schema declares.
      for (Json::json_pointer q = p.parent_pointer(); !q.empty() && !doc.contains(q); q = q.parent_pointer()) {
        const KeySchema* k = schema ? schema->key_at(q.to_string()) : nullptr;
        if (!k || k->type != "object")
          throw ScenarioError(ptr, "override target's parent does not exist in the scenario");
      }
    }
    doc[p] = std::move(value);
  } catch (const Json::exception& e) {
    throw ScenarioError(ptr, std::string("cannot apply override: ") + e.what());
  }
}

ScenarioDocument ScenarioDocument::load(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                                        const ObjectSchema* schema) {
  std::vector<std::filesystem::path> chain;
  Json doc = load_with_includes(file, chain);
  for (const auto& o : overrides) apply_override(doc, o, schema);
  auto dir = file.parent_path();
  if (dir.empty()) dir = ".";
  return from_json(std::move(doc), dir);
}

ScenarioDocument ScenarioDocument::from_json(Json doc, std::filesystem::path base_dir) {
  ScenarioDocument d;
  if (!doc.is_object()) throw ScenarioError("", "a scenario must be a JSON object");
  d.doc_ = std::move(doc);
  d.log_ = std::make_shared<ReadLog>();
  d.log_->resolved = d.doc_;
  d.log_->base_dir = std::move(base_dir);
  return d;
}

ConfigNode ScenarioDocument::root() const { return ConfigNode(&doc_, "", log_); }

void ScenarioDocument::resolve(const std::string& pointer, Json value) const {
  log_->resolved[Json::json_pointer(pointer)] = std::move(value);
}

void ScenarioDocument::check_unknown_keys(const ObjectSchema* schema, std::vector<std::string>* warnings) const {
  // Depth-first in document order, so the first problem reported is stable.
  std::vector<std::pair<const Json*, std::string>> stack{{&doc_, ""}};
  while (!stack.empty()) {
    auto [n, p] = stack.back();
    stack.pop_back();
    std::vector<std::pair<const Json*, std::string>> kids;
    if (n->is_object()) {
      for (auto it = n->begin(); it != n->end(); ++it) kids.emplace_back(&*it, join_pointer(p, it.key()));
    } else if (n->is_array()) {
      for (size_t i = 0; i < n->size(); ++i)
        if ((*n)[i].is_object()) kids.emplace_back(&(*n)[i], join_pointer(p, std::to_string(i)));
    }
    std::vector<std::pair<const Json*, std::string>> read;
    for (auto& k : kids) {
      if (log_->read_pointers.count(k.second)) {
        read.push_back(k);
        continue;
      }
      const bool array_elem = n->is_array();
      const KeySchema* declared = schema && !array_elem ? schema->key_at(k.second) : nullptr;
      if (declared) {
        std::string when;
        for (const auto& m : declared->modes) when += (when.empty() ? "" : "; or ") + m;
        if (warnings)
          warnings->push_back(k.second + ": ignored: " +
                              (when.empty() ? std::string("not read by this scenario") : "read only when " + when));
        continue;
      }
      throw ScenarioError(k.second, array_elem ? "entry was not used by the scenario"
                                               : "unknown key (check its spelling, or remove it: nothing reads it)");
    }
    for (auto it = read.rbegin(); it != read.rend(); ++it) stack.push_back(*it);
  }
}

}  // namespace latsim::scenario
