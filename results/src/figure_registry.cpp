#include "latsim/results/figure_registry.hpp"

#include <algorithm>
#include <cctype>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace latsim::results {

// The text of results/figure_registry.json, embedded by the build.
extern const std::string_view kFigureRegistryJson;

namespace {

using Json = nlohmann::json;

const std::set<std::string> kKinds = {"distribution", "count", "number", "flag", "word",
                                      "list",         "object", "group", "summary"};
const std::set<std::string> kShown = {"always", "where present", "when leading"};

[[noreturn]] void bad(const std::string& where, const std::string& what) {
  throw std::invalid_argument("figure registry: " + where + ": " + what);
}

std::string text(const Json& j, const char* key, const std::string& where, bool required = true) {
  if (!j.contains(key)) {
    if (required) bad(where, std::string("needs \"") + key + "\"");
    return {};
  }
  if (!j.at(key).is_string()) bad(where, std::string("\"") + key + "\" must be a string");
  return j.at(key).get<std::string>();
}

FigureColumn column_of(const Json& c, const std::string& where) {
  FigureColumn col;
  if (!c.is_object() || !c.contains("order") || !c.at("order").is_number_integer())
    bad(where, "a column needs an integer \"order\"");
  col.order = c.at("order").get<int>();
  col.name = text(c, "name", where);
  col.figure = text(c, "figure", where);
  col.label = text(c, "label", where);
  col.shown = c.contains("shown") ? text(c, "shown", where) : "always";
  if (kShown.count(col.shown) == 0) bad(where, "column " + col.name + ": \"shown\" is always, where present or when leading");
  if (c.contains("report")) {
    if (!c.at("report").is_boolean()) bad(where, "column " + col.name + ": \"report\" must be true or false");
    col.report = c.at("report").get<bool>();
  }
  return col;
}

FigureDecl decl_of(const Json& f, size_t index) {
  const std::string where = "figures[" + std::to_string(index) + "]";
  if (!f.is_object()) bad(where, "must be an object");
  FigureDecl d;
  d.name = text(f, "name", where);
  const std::string at = where + " (" + d.name + ")";
  d.kind = text(f, "kind", at);
  if (kKinds.count(d.kind) == 0) bad(at, "unknown kind \"" + d.kind + "\"");
  d.unit = text(f, "unit", at);
  d.family = text(f, "family", at);
  d.meaning = text(f, "meaning", at);
  if (d.meaning.empty()) bad(at, "says nothing of what it means");
  const Json& p = f.contains("pipelines") ? f.at("pipelines") : Json();
  if (p.is_string() && p.get<std::string>() == "all") {
    // any pipeline
  } else if (p.is_array() && !p.empty()) {
    for (const Json& name : p) {
      if (!name.is_string()) bad(at, "\"pipelines\" lists pipeline names");
      d.pipelines.push_back(name.get<std::string>());
    }
  } else {
    bad(at, "\"pipelines\" is \"all\" or a list of pipeline names");
  }
  if (f.contains("headline")) {
    if (!f.at("headline").is_object()) bad(at, "\"headline\" maps headline sets to ranks");
    for (const auto& [set, rank] : f.at("headline").items()) {
      if (!rank.is_number_integer() || rank.get<int>() < 1) bad(at, "headline rank of " + set + " must be 1 or more");
      d.headline[set] = rank.get<int>();
    }
  }
  if (f.contains("columns")) {
    if (!f.at("columns").is_array()) bad(at, "\"columns\" must be a list");
    for (const Json& c : f.at("columns")) d.columns.push_back(column_of(c, at));
  }
  return d;
}

bool has_placeholder(std::string_view name) { return name.find('<') != std::string_view::npos; }

}  // namespace

bool FigureDecl::produced_by(std::string_view pipeline) const {
  return pipelines.empty() || std::find(pipelines.begin(), pipelines.end(), pipeline) != pipelines.end();
}

std::string_view FigureRegistry::builtin_text() { return kFigureRegistryJson; }

const FigureRegistry& FigureRegistry::builtin() {
  static const FigureRegistry registry = parse(kFigureRegistryJson);
  return registry;
}

FigureRegistry FigureRegistry::parse(std::string_view json_text) {
  const Json doc = Json::parse(json_text.begin(), json_text.end(), nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) bad("the file", "is not a JSON object");
  FigureRegistry r;
  if (doc.contains("placeholders"))
    for (const auto& [name, words] : doc.at("placeholders").items()) {
      if (name == "n" || !words.is_array() || words.empty()) bad("placeholders." + name, "lists the words it stands for");
      for (const Json& w : words) r.placeholders_[name].push_back(w.get<std::string>());
    }
  if (!doc.contains("families") || !doc.at("families").is_object()) bad("the file", "needs an object \"families\"");
  for (const auto& [name, family] : doc.at("families").items()) {
    if (!family.is_object() || !family.contains("glossary") || !family.at("glossary").is_boolean())
      bad("families." + name, "needs \"glossary\": true or false");
    r.families_[name] = family.at("glossary").get<bool>();
  }
  if (!doc.contains("headlines") || !doc.at("headlines").is_object()) bad("the file", "needs an object \"headlines\"");
  for (const auto& [set, about] : doc.at("headlines").items()) {
    if (!about.is_object() || !about.contains("used_by")) bad("headlines." + set, "needs \"used_by\"");
    r.headlines_[set] = HeadlineSet{about.at("used_by").get<std::string>(), about.value("why", std::string())};
  }
  if (!doc.contains("figures") || !doc.at("figures").is_array()) bad("the file", "needs a list \"figures\"");
  const Json& figures = doc.at("figures");
  for (size_t i = 0; i < figures.size(); ++i) r.figures_.push_back(decl_of(figures[i], i));

  std::set<int> orders;
  for (size_t i = 0; i < r.figures_.size(); ++i) {
    const FigureDecl& d = r.figures_[i];
    const std::string at = "figure " + d.name;
    if (r.families_.count(d.family) == 0) bad(at, "family \"" + d.family + "\" is not among \"families\"");
    for (const auto& [set, rank] : d.headline)
      if (r.headlines_.count(set) == 0) bad(at, "headline set \"" + set + "\" is not among \"headlines\"");
    for (size_t k = 0; k < d.name.size(); ++k) {
      if (d.name[k] != '<') continue;
      const size_t end = d.name.find('>', k);
      if (end == std::string::npos) bad(at, "a placeholder is not closed");
      const std::string ph = d.name.substr(k + 1, end - k - 1);
      if (ph != "n" && r.placeholders_.count(ph) == 0) bad(at, "placeholder <" + ph + "> is not among \"placeholders\"");
    }
    for (const FigureColumn& c : d.columns) {
      if (!orders.insert(c.order).second) bad(at, "column order " + std::to_string(c.order) + " is taken");
      r.columns_.push_back(c);
    }
    if (has_placeholder(d.name)) {
      r.patterns_.push_back(i);
    } else if (!r.exact_.emplace(d.name, i).second) {
      bad(at, "is declared twice");
    }
  }
  for (size_t i = 0; i < r.patterns_.size(); ++i)
    for (size_t k = 0; k < i; ++k)
      if (r.figures_[r.patterns_[i]].name == r.figures_[r.patterns_[k]].name)
        bad("figure " + r.figures_[r.patterns_[i]].name, "is declared twice");
  std::sort(r.columns_.begin(), r.columns_.end(), [](const FigureColumn& a, const FigureColumn& b) { return a.order < b.order; });
  for (size_t i = 0; i < r.columns_.size(); ++i)
    if (r.columns_[i].order != static_cast<int>(i) + 1) bad("column " + r.columns_[i].name, "orders run 1, 2, 3, ... without gaps");
  for (const auto& [set, used_by] : r.headlines_) {
    std::set<int> ranks;
    for (const FigureDecl& d : r.figures_) {
      const auto it = d.headline.find(set);
      if (it != d.headline.end() && !ranks.insert(it->second).second)
        bad("headline " + set, "rank " + std::to_string(it->second) + " is given twice");
    }
    if (ranks.empty()) bad("headline " + set, "no figure is ranked in it");
  }
  return r;
}

const std::vector<std::string>& FigureRegistry::placeholder(std::string_view name) const {
  const auto it = placeholders_.find(std::string(name));
  if (it == placeholders_.end()) throw std::logic_error("figure registry: no placeholder <" + std::string(name) + ">");
  return it->second;
}

bool FigureRegistry::matches(std::string_view pattern, std::string_view name) const {
  if (pattern.empty()) return name.empty();
  if (pattern.front() != '<') return !name.empty() && name.front() == pattern.front() && matches(pattern.substr(1), name.substr(1));
  const size_t close = pattern.find('>');
  const std::string_view ph = pattern.substr(1, close - 1);
  const std::string_view rest = pattern.substr(close + 1);
  if (ph == "n") {
    // One or more digits, the shortest that lets the rest match.
    for (size_t k = 0; k < name.size() && std::isdigit(static_cast<unsigned char>(name[k])); ++k)
      if (matches(rest, name.substr(k + 1))) return true;
    return false;
  }
  for (const std::string& word : placeholders_.at(std::string(ph)))
    if (name.starts_with(word) && matches(rest, name.substr(word.size()))) return true;
  return false;
}

const FigureDecl* FigureRegistry::find_in(std::string_view name, int depth) const {
  if (const auto it = exact_.find(std::string(name)); it != exact_.end() && figures_[it->second].kind != "group")
    return &figures_[it->second];
  for (size_t i : patterns_)
    if (figures_[i].kind != "group" && matches(figures_[i].name, name)) return &figures_[i];
  // A member of a group: "variants.0.render_load" is render_load.
  if (depth > 4) return nullptr;
  for (const FigureDecl& g : figures_) {
    if (g.kind != "group") continue;
    for (size_t dot = name.find('.'); dot != std::string_view::npos; dot = name.find('.', dot + 1)) {
      if (!matches(g.name, name.substr(0, dot))) continue;
      if (const FigureDecl* member = find_in(name.substr(dot + 1), depth + 1)) return member;
    }
  }
  return nullptr;
}

const FigureDecl* FigureRegistry::find(std::string_view name) const { return find_in(name, 0); }

bool FigureRegistry::in_glossary(const FigureDecl& d) const {
  const auto it = families_.find(d.family);
  return it != families_.end() && it->second;
}

std::vector<std::string> FigureRegistry::headline(std::string_view set) const {
  if (!has_headline(set))
    throw std::logic_error("headline \"" + std::string(set) + "\" is not declared in results/figure_registry.json");
  std::vector<std::pair<int, std::string>> ranked;
  for (const FigureDecl& d : figures_) {
    const auto it = d.headline.find(std::string(set));
    if (it != d.headline.end()) ranked.emplace_back(it->second, d.name);
  }
  std::sort(ranked.begin(), ranked.end());
  std::vector<std::string> names;
  for (auto& [rank, name] : ranked) names.push_back(std::move(name));
  return names;
}

}  // namespace latsim::results
