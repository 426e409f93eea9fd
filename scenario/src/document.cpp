// Scenario documents: a file with its includes merged and its overrides
// applied, and the check that every key in it was read.
#include <cerrno>
#include <cstdlib>
#include <filesystem>

#include "latsim/scenario/config.hpp"
#include "latsim/scenario/json_text.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/scenario/schema.hpp"
#include "section_internal.hpp"

namespace latsim::scenario {

using Json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

// Cycles are caught separately; a chain of distinct files this long is a mistake.
constexpr size_t kMaxIncludeDepth = 16;

// Objects merge key by key; anything else in `over` replaces `base`. An
// object whose "type" differs from the base's is a different thing altogether
// (a trace instead of a sinusoid) and replaces it whole. Recursion is bounded
// by the nesting limit of parse_json.
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

// The files a document includes: the pointer of each name, the file, and its
// directory as the name gives it (what its relative paths are rebased by).
struct Include {
  std::string where;
  fs::path file;
  fs::path named_dir;
};

std::vector<Include> includes_of(const Json& doc, const fs::path& file) {
  std::vector<Include> out;
  const Json& inc = doc["include"];
  const auto add = [&](const std::string& where, const Json& name) {
    if (!name.is_string() || name.get<std::string>().empty())
      throw ScenarioError(where, "expected a file name, got " + (name.is_string() ? std::string("\"\"") : json_type_name(name)), file);
    if (name.get_ref<const std::string&>().find('\0') != std::string::npos)
      throw ScenarioError(where, "contains a NUL character (\\u0000)", file);
    fs::path p = name.get<std::string>();
    out.push_back({where, p.is_relative() ? file.parent_path() / p : p, p.parent_path()});
  };
  if (inc.is_array()) {
    for (size_t i = 0; i < inc.size(); ++i) add("/include/" + std::to_string(i), inc[i]);
  } else if (inc.is_string()) {
    add("/include", inc);
  } else {
    throw ScenarioError("/include", "expected a file name or an array of file names, got " + json_type_name(inc), file);
  }
  return out;
}

// A relative file name is relative to the file that names it. An included
// file's relative paths (the keys the schema declares as paths) are rebased
// onto the including file's directory by `dir`, the included file's directory
// as the including file named it, so the merged document reads as if written
// in the including file. Without a schema nothing is known to be a path.
void rebase_paths(Json& doc, const fs::path& dir, const ObjectSchema* schema) {
  if (!schema || !doc.is_object() || dir.empty()) return;
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    const KeySchema* key = schema->find(it.key());
    if (!key) continue;
    Json& value = it.value();
    if (key->type == "path" && value.is_string()) {
      const fs::path p = value.get<std::string>();
      if (!p.empty() && p.is_relative()) value = (dir / p).lexically_normal().generic_string();
    } else if (key->type == "object" && key->object) {
      rebase_paths(value, dir, key->object.get());
    } else if (key->type == "objects" && key->object && value.is_array()) {
      for (Json& item : value) rebase_paths(item, dir, key->object.get());
    }
  }
}

Json load_with_includes(const fs::path& file, std::vector<fs::path>& chain, const ObjectSchema* schema);

// `doc`, read from `file` (the last of `chain`), with the files it includes
// merged under it: theirs first, in order, then its own keys over them.
Json merge_includes(Json doc, const fs::path& file, std::vector<fs::path>& chain, const ObjectSchema* schema) {
  if (!doc.is_object()) throw ScenarioError("", "a scenario must be a JSON object, not " + json_type_name(doc), file);
  Json result = Json::object();
  if (doc.contains("include")) {
    for (const auto& [where, included, named_dir] : includes_of(doc, file)) {
      std::error_code canon_ec;
      fs::path included_canon = fs::weakly_canonical(included, canon_ec);
      if (canon_ec) included_canon = included.lexically_normal();
      for (const auto& c : chain)
        if (c == included_canon) throw ScenarioError(where, "include cycle through " + quote_value(included.string()), file);
      if (chain.size() >= kMaxIncludeDepth)
        throw ScenarioError(where, "includes nest more than " + std::to_string(kMaxIncludeDepth) + " files deep", file);
      // A file that cannot be read is a problem of the include naming it.
      std::error_code status_ec;
      const fs::file_status st = fs::status(included, status_ec);
      if (status_ec || !fs::is_regular_file(st)) {
        const std::string why = status_ec ? status_ec.message()
                                : fs::is_directory(st) ? std::string("it is a directory")
                                                       : std::string("it is not a regular file (a device, pipe or socket)");
        throw ScenarioError(where, "cannot read the included file " + quote_value(included.string()) + ": " + why, file);
      }
      try {
        Json included_doc = load_with_includes(included, chain, schema);
        rebase_paths(included_doc, named_dir, schema);
        deep_merge(result, included_doc);
      } catch (const ScenarioError& e) {
        // Name the chain: the file, and the pointer in it, that included the one at fault.
        throw ScenarioError(e.pointer(), e.message() + " (included by " + file.string() + " at " + where + ")",
                            e.file().empty() ? included : e.file());
      }
    }
    doc.erase("include");
  }
  deep_merge(result, doc);
  return result;
}

// Where a file stands in a chain of includes: its canonical path when it has one.
fs::path chain_entry(const fs::path& file) {
  std::error_code ec;
  fs::path canon = fs::weakly_canonical(file, ec);
  return ec ? file.lexically_normal() : canon;
}

Json load_with_includes(const fs::path& file, std::vector<fs::path>& chain, const ObjectSchema* schema) {
  chain.push_back(chain_entry(file));
  Json result =
      merge_includes(read_json_file(file, chain.size() == 1 ? "scenario file" : "included file"), file, chain, schema);
  chain.pop_back();
  return result;
}

// The unescaped segments of a JSON pointer given on the command line.
std::vector<std::string> pointer_segments(const std::string& pointer) {
  std::vector<std::string> out;
  for (size_t i = 0; i < pointer.size();) {
    std::string segment;
    size_t j = i + 1;
    for (; j < pointer.size() && pointer[j] != '/'; ++j) {
      if (pointer[j] != '~') {
        segment += pointer[j];
        continue;
      }
      if (j + 1 >= pointer.size() || (pointer[j + 1] != '0' && pointer[j + 1] != '1'))
        throw ScenarioError(pointer, "not a valid JSON pointer: '~' must be followed by 0 or 1");
      segment += pointer[++j] == '0' ? '~' : '/';
    }
    out.push_back(std::move(segment));
    i = j;
  }
  return out;
}

// An array index in a pointer: digits without a leading zero, or "-" (one past the end).
std::optional<size_t> array_index(const std::string& segment, size_t size) {
  if (segment == "-") return size;
  if (segment.empty() || segment.size() > 18 || (segment.size() > 1 && segment[0] == '0')) return std::nullopt;
  for (char c : segment)
    if (c < '0' || c > '9') return std::nullopt;
  return static_cast<size_t>(std::strtoull(segment.c_str(), nullptr, 10));
}

}  // namespace

void apply_override(Json& doc, const std::string& assignment, const ObjectSchema* schema) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || assignment.empty() || assignment[0] != '/')
    throw ScenarioError("", "override " + quote_value(assignment) + " must look like /json/pointer=value");
  const std::string ptr = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  std::optional<Json> parsed;
  try {
    parsed = parse_json_value(text, "--set");
  } catch (const ScenarioError& e) {
    throw ScenarioError(ptr + e.pointer(), "in the --set value: " + e.message());
  }
  if (!parsed) {
    // A bare word is a string, but only as text JSON can hold.
    if (readable(text, text.size() + 1) != text)
      throw ScenarioError(ptr, "override value " + quote_value(text) + " holds control characters or is not UTF-8 text");
    parsed = Json(text);
  }
  const std::vector<std::string> segments = pointer_segments(ptr);
  Json* node = &doc;
  std::string walked;
  for (size_t i = 0; i < segments.size(); ++i) {
    const std::string& segment = segments[i];
    const bool last = i + 1 == segments.size();
    const std::string here = join_pointer(walked, segment);
    if (node->is_array()) {
      const auto index = array_index(segment, node->size());
      if (!index || *index > node->size() || (!last && *index == node->size()))
        throw ScenarioError(here, "no such entry: " + readable_pointer(walked) + " has " +
                                      std::to_string(node->size()) + " entries");
      if (*index == node->size()) node->push_back(Json());
      node = &(*node)[*index];
    } else if (node->is_object()) {
      if (!last && !node->contains(segment)) {
        // A missing ancestor must be an object the schema declares (an optional section).
        const KeySchema* k = schema ? schema->key_at(here) : nullptr;
        if (!k || k->type != "object")
          throw ScenarioError(ptr, "override target's parent " + readable_pointer(here) + " does not exist in the scenario");
        (*node)[segment] = Json::object();
      }
      node = &(*node)[segment];
    } else {
      throw ScenarioError(ptr, "cannot set a key inside " + readable_pointer(walked) + ", which is " + json_type_name(*node));
    }
    walked = here;
  }
  *node = std::move(*parsed);
}

ScenarioDocument ScenarioDocument::load(const fs::path& file, const std::vector<std::string>& overrides,
                                        const ObjectSchema* schema) {
  std::vector<fs::path> chain;
  Json doc = load_with_includes(file, chain, schema);
  for (const auto& o : overrides) apply_override(doc, o, schema);
  auto dir = file.parent_path();
  if (dir.empty()) dir = ".";
  return from_json(std::move(doc), dir);
}

ScenarioDocument ScenarioDocument::parse(std::string_view text, const fs::path& name,
                                         const std::vector<std::string>& overrides, const ObjectSchema* schema) {
  std::vector<fs::path> chain{chain_entry(name)};
  Json doc = merge_includes(parse_json(text, name.string()), name, chain, schema);
  for (const auto& o : overrides) apply_override(doc, o, schema);
  auto dir = name.parent_path();
  if (dir.empty()) dir = ".";
  return from_json(std::move(doc), dir);
}

ScenarioDocument ScenarioDocument::from_json(Json doc, fs::path base_dir) {
  ScenarioDocument d;
  if (!doc.is_object()) throw ScenarioError("", "a scenario must be a JSON object");
  d.doc_ = std::move(doc);
  d.log_ = std::make_shared<ReadLog>();
  d.log_->resolved = d.doc_;
  d.log_->base_dir = std::move(base_dir);
  return d;
}

ConfigNode ScenarioDocument::root() const { return ConfigNode(&doc_, "", log_); }

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
        // Not read, yet it must still be a value its declaration accepts.
        const KeySchema* parent = p.empty() ? nullptr : schema->key_at(p);
        const ObjectSchema* parent_schema = p.empty() ? schema : (parent ? parent->object.get() : nullptr);
        if (parent_schema) check_unread_value(*parent_schema, pointer_segments(k.second).back(), *k.first, p);
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
