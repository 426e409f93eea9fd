#include "latsim/scenario/schema.hpp"

#include <sstream>

namespace latsim::scenario {

using Json = nlohmann::json;

namespace {

// Splits a JSON pointer into its unescaped segments.
std::vector<std::string> segments(std::string_view pointer) {
  std::vector<std::string> out;
  size_t i = 0;
  while (i < pointer.size()) {
    if (pointer[i] != '/') return {};
    ++i;
    std::string seg;
    while (i < pointer.size() && pointer[i] != '/') {
      if (pointer[i] == '~' && i + 1 < pointer.size()) {
        seg += pointer[i + 1] == '1' ? '/' : '~';
        i += 2;
      } else {
        seg += pointer[i++];
      }
    }
    out.push_back(std::move(seg));
  }
  return out;
}

Json object_json(const ObjectSchema& o);

void add_bounds(Json& j, const KeySchema& k) {
  if (k.min) j[k.above_min ? "exclusiveMinimum" : "minimum"] = *k.min;
  if (k.max) j["maximum"] = *k.max;
}

Json value_json(const KeySchema& k) {
  Json j;
  if (k.type == "number" || k.type == "duration") {
    j = {{"type", "number"}};
    add_bounds(j, k);
  } else if (k.type == "integer") {
    j = {{"type", "integer"}};
    add_bounds(j, k);
  } else if (k.type == "boolean") {
    j = {{"type", "boolean"}};
  } else if (k.type == "string") {
    j = {{"type", "string"}};
  } else if (k.type == "path") {
    j = {{"type", "string"}, {"minLength", 1}};
  } else if (k.type == "choice") {
    j = {{"enum", k.choices}};
  } else if (k.type == "choices") {
    j = {{"type", "array"}, {"items", {{"enum", k.choices}}}};
  } else if (k.type == "rate") {
    Json number{{"type", "number"}};
    add_bounds(number, k);
    if (!k.min) number["exclusiveMinimum"] = 0;
    j = {{"anyOf", Json::array({number, Json{{"type", "string"}, {"pattern", "^[0-9]+(/[0-9]+)?$"}}})}};
  } else if (k.type == "numbers") {
    Json item{{"type", "number"}};
    add_bounds(item, k);
    j = {{"type", "array"}, {"items", item}};
    if (k.count > 0) j["minItems"] = j["maxItems"] = k.count;
  } else if (k.type == "number_rows") {
    Json item{{"type", "number"}};
    add_bounds(item, k);
    Json row{{"type", "array"}, {"items", item}};
    if (k.row_count > 0) row["minItems"] = row["maxItems"] = k.row_count;
    j = {{"type", "array"}, {"items", row}};
  } else if (k.type == "object") {
    j = object_json(*k.object);
  } else if (k.type == "objects") {
    j = {{"type", "array"}, {"items", object_json(*k.object)}};
  }
  std::string description = k.doc;
  if (!k.unit.empty()) description += " [" + k.unit + "]";
  if (!k.default_doc.empty()) description += " (default: " + k.default_doc + ")";
  if (!description.empty()) j["description"] = description;
  if (!k.default_value.is_null()) j["default"] = k.default_value;
  return j;
}

Json object_json(const ObjectSchema& o) {
  Json props = Json::object();
  Json required = Json::array();
  for (const KeySchema& k : o.keys) {
    if (props.contains(k.name)) {
      // The same name read by different modes with different meanings: either.
      Json& p = props[k.name];
      if (!p.contains("anyOf") || !p.contains("x-modes")) p = {{"anyOf", Json::array({p})}, {"x-modes", true}};
      p["anyOf"].push_back(value_json(k));
      continue;
    }
    props[k.name] = value_json(k);
    if (k.required && k.modes.empty()) required.push_back(k.name);
  }
  for (auto& [name, p] : props.items())
    if (p.contains("x-modes")) p.erase("x-modes");
  Json j{{"type", "object"}, {"properties", props}, {"additionalProperties", false}};
  if (!required.empty()) j["required"] = required;
  if (!o.doc.empty()) j["description"] = o.doc.substr(0, o.doc.find('\n'));
  return j;
}

// ---- Markdown ------------------------------------------------------------

std::string code(const std::string& s) { return "`" + s + "`"; }

std::string number_text(double x) {
  std::ostringstream s;
  if (x == static_cast<double>(static_cast<int64_t>(x)) && x > -1e15 && x < 1e15) {
    // Round powers of ten read better as 1e12 than as thirteen digits.
    int64_t mantissa = static_cast<int64_t>(x);
    int exponent = 0;
    while (mantissa != 0 && mantissa % 10 == 0) mantissa /= 10, ++exponent;
    if (exponent >= 6) s << mantissa << "e" << exponent;
    else s << static_cast<int64_t>(x);
  } else {
    s << x;
  }
  return s.str();
}

void rules_markdown(std::ostringstream& md, const ObjectSchema& o, const std::string& mode) {
  bool any = false;
  for (const auto& [m, rule] : o.rules) {
    if (m != mode && !(mode.empty() ? false : m.rfind(mode + ",", 0) == 0)) continue;
    if (!any) md << "Checks:\n\n";
    any = true;
    md << "- " << rule << "\n";
  }
  if (any) md << "\n";
}

std::string default_text(const KeySchema& k) {
  if (k.required) return "**required**";
  if (!k.default_doc.empty()) return k.default_doc;
  if (k.default_value.is_null()) return "—";
  if (k.default_value.is_string())
    return k.default_value.get<std::string>().empty() ? "`\"\"`" : code(k.default_value.get<std::string>());
  return code(k.default_value.dump());
}

std::string range_text(const KeySchema& k) {
  std::string r;
  if (k.type == "choice" || k.type == "choices") {
    for (const auto& c : k.choices) r += (r.empty() ? "" : ", ") + code(c);
    return r;
  }
  if (k.min && k.max) r = (k.above_min ? "(" : "[") + number_text(*k.min) + ", " + number_text(*k.max) + "]";
  else if (k.min) r = (k.above_min ? "> " : "≥ ") + number_text(*k.min);
  else if (k.max) r = "≤ " + number_text(*k.max);
  if (k.count > 0) r += (r.empty() ? "" : ", ") + std::to_string(k.count) + " numbers";
  if (k.row_count > 0) r += (r.empty() ? "" : ", ") + std::to_string(k.row_count) + " per row";
  return r;
}

std::string type_text(const KeySchema& k) {
  if (k.type == "rate") return "rate (Hz)";
  if (k.type == "number_rows") return "rows of numbers";
  if (k.type == "objects") return "array of objects";
  if (k.type == "choices") return "array of choices";
  return k.type;
}

// Conditions of `k` beyond `prefix` (the mode whose table lists it).
std::string condition_text(const KeySchema& k, const std::string& prefix) {
  std::string out;
  for (const auto& m : k.modes) {
    if (!prefix.empty() && m.rfind(prefix, 0) != 0) continue;
    std::string rest = m.substr(prefix.size());
    if (rest.rfind(", ", 0) == 0) rest = rest.substr(2);
    if (rest.empty()) return "";
    out += (out.empty() ? "" : "; or ") + rest;
  }
  return out;
}

void key_table(std::ostringstream& md, const std::vector<const KeySchema*>& keys, const std::string& prefix) {
  if (keys.empty()) return;
  bool conditional = false;
  for (const KeySchema* k : keys) conditional = conditional || !condition_text(*k, prefix).empty();
  md << "| key | type | default | range | unit |" << (conditional ? " read when |" : "") << " meaning |\n";
  md << "| --- | --- | --- | --- | --- |" << (conditional ? " --- |" : "") << " --- |\n";
  for (const KeySchema* k : keys) {
    md << "| " << code(k->name) << " | " << type_text(*k) << " | " << default_text(*k) << " | " << range_text(*k)
       << " | " << k->unit << " |";
    if (conditional) md << " " << condition_text(*k, prefix) << " |";
    md << " " << k->doc << (k->object ? " (below)" : "") << " |\n";
  }
  md << "\n";
}

void object_markdown(std::ostringstream& md, const ObjectSchema& o, const std::string& path, int level);

void nested_markdown(std::ostringstream& md, const std::vector<const KeySchema*>& keys, const std::string& path,
                     int level) {
  for (const KeySchema* k : keys) {
    if (!k->object) continue;
    const std::string sub = path.empty() ? k->name : path + "." + k->name;
    md << std::string(static_cast<size_t>(level), '#') << " " << code(sub)
       << (k->type == "objects" ? " (each entry)" : "") << "\n\n";
    object_markdown(md, *k->object, sub, level + 1);
  }
}

void object_markdown(std::ostringstream& md, const ObjectSchema& o, const std::string& path, int level) {
  if (!o.doc.empty()) md << o.doc << "\n\n";
  std::vector<const KeySchema*> common;
  for (const KeySchema& k : o.keys)
    if (k.modes.empty()) common.push_back(&k);
  key_table(md, common, "");
  rules_markdown(md, o, "");
  nested_markdown(md, common, path, level);
  if (!o.discriminators.empty()) {
    const ObjectSchema::Discriminator& d = o.discriminators.front();
    for (const auto& [value, doc] : d.values) {
      const std::string prefix = d.key + "=" + value;
      std::vector<const KeySchema*> keys;
      for (const KeySchema& k : o.keys)
        for (const auto& m : k.modes)
          if (m == prefix || m.rfind(prefix + ",", 0) == 0) {
            keys.push_back(&k);
            break;
          }
      md << std::string(static_cast<size_t>(level), '#') << " " << code(path) << " with " << code(d.key) << " "
         << code(value) << "\n\n";
      if (!doc.empty()) md << doc << "\n\n";
      if (keys.empty()) md << "No further keys.\n\n";
      key_table(md, keys, prefix);
      rules_markdown(md, o, prefix);
      nested_markdown(md, keys, path, level + 1);
    }
  }
}

}  // namespace

const KeySchema* ObjectSchema::find(std::string_view key) const {
  for (const KeySchema& k : keys)
    if (k.name == key) return &k;
  return nullptr;
}

const KeySchema* ObjectSchema::key_at(std::string_view pointer) const {
  const std::vector<std::string> segs = segments(pointer);
  const ObjectSchema* object = this;
  const KeySchema* key = nullptr;
  for (size_t i = 0; i < segs.size(); ++i) {
    if (!object) return key;  // inside a declared non-object value (an array of numbers)
    key = object->find(segs[i]);
    if (!key) return nullptr;
    object = key->object.get();
    if (key->type == "objects") ++i;  // the array index
  }
  return key;
}

// The same schema with no key required anywhere.
Json without_required(Json j) {
  if (j.is_object()) {
    j.erase("required");
    for (auto& [key, value] : j.items()) value = without_required(value);
  } else if (j.is_array()) {
    for (auto& value : j) value = without_required(value);
  }
  return j;
}

Json json_schema(const ObjectSchema& root) {
  Json strict = object_json(root);
  strict["properties"]["include"] = {
      {"description",
       "a base scenario file (or a list), relative to this file, merged under this one; a relative file name "
       "in an included file stays relative to that file"},
      {"anyOf", Json::array({Json{{"type", "string"}},
                             Json{{"type", "array"}, {"items", {{"type", "string"}}}}})}};
  // A file that includes a base may leave anything, required or not, to the base.
  return Json{{"$schema", "http://json-schema.org/draft-07/schema#"},
              {"title", "latsim scenario"},
              {"description", strict.value("description", "")},
              {"if", {{"required", Json::array({"include"})}}},
              {"then", without_required(strict)},
              {"else", strict}};
}

std::string markdown_reference(const ObjectSchema& root) {
  std::ostringstream md;
  md << "# Scenario reference\n\n"
     << "<!-- Generated by `latsim schema --format markdown` from the parameter declarations; do not edit. -->\n\n";
  if (!root.doc.empty()) md << root.doc << "\n\n";
  md << "## Top level\n\n";
  std::vector<const KeySchema*> scalars;
  for (const KeySchema& k : root.keys)
    if (!k.object) scalars.push_back(&k);
  md << "| key | type | default | range | unit | meaning |\n| --- | --- | --- | --- | --- | --- |\n"
     << "| `include` | string or array | — |  |  | a base scenario file (or a list), relative to this file; objects "
        "merge key by key, an object whose `type` changes replaces the base's; a relative file name in an included file stays relative to that file |\n";
  for (const KeySchema* k : scalars)
    md << "| " << code(k->name) << " | " << type_text(*k) << " | " << default_text(*k) << " | " << range_text(*k)
       << " | " << k->unit << " | " << k->doc << " |\n";
  md << "\n";
  for (const KeySchema& k : root.keys) {
    if (!k.object) continue;
    md << "## " << code(k.name) << (k.required ? " (**required**)" : "") << (k.doc.empty() ? "" : ": " + k.doc)
       << "\n\n";
    object_markdown(md, *k.object, k.name, 3);
  }
  return md.str();
}

}  // namespace latsim::scenario
