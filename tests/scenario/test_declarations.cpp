// Each scenario key is declared exactly once: a walk over the schema and over
// every shipped scenario as it runs (every default applied).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "latsim/run/runner.hpp"

using latsim::scenario::KeySchema;
using latsim::scenario::ObjectSchema;
using Json = nlohmann::json;

namespace {

std::vector<std::string> conditions_of(const std::string& mode) {
  std::vector<std::string> out;
  std::stringstream in(mode);
  std::string part;
  while (std::getline(in, part, ',')) out.push_back(part.substr(part.find_first_not_of(' ')));
  return out;
}

// Whether a declaration is read when the discriminators have the values in `in_force`.
bool applies(const KeySchema& k, const std::set<std::string>& in_force) {
  if (k.modes.empty()) return true;
  for (const auto& mode : k.modes) {
    bool all = true;
    for (const auto& c : conditions_of(mode)) all = all && in_force.count(c) != 0;
    if (all) return true;
  }
  return false;
}

void walk(const Json& object, const ObjectSchema& schema, const std::string& pointer) {
  std::set<std::string> in_force;
  for (const auto& d : schema.discriminators)
    if (object.contains(d.key) && object[d.key].is_string()) in_force.insert(d.key + "=" + object[d.key].get<std::string>());
  for (const auto& [name, value] : object.items()) {
    int declarations = 0;
    const KeySchema* found = nullptr;
    for (const KeySchema& k : schema.keys)
      if (k.name == name && applies(k, in_force)) {
        ++declarations;
        found = &k;
      }
    INFO(pointer + "/" + name);
    REQUIRE(declarations == 1);
    if (!found->object) continue;
    if (found->type == "object") walk(value, *found->object, pointer + "/" + name);
    if (found->type == "objects")
      for (size_t i = 0; i < value.size(); ++i)
        walk(value[i], *found->object, pointer + "/" + name + "/" + std::to_string(i));
  }
}

// No object declares one name twice for any one mode.
void check_unique(const ObjectSchema& schema, const std::string& path) {
  for (size_t i = 0; i < schema.keys.size(); ++i) {
    const KeySchema& a = schema.keys[i];
    for (size_t j = i + 1; j < schema.keys.size(); ++j) {
      const KeySchema& b = schema.keys[j];
      if (a.name != b.name) continue;
      INFO(path + "/" + a.name);
      REQUIRE_FALSE(a.modes.empty());
      REQUIRE_FALSE(b.modes.empty());
      for (const auto& m : a.modes)
        for (const auto& n : b.modes) CHECK(m != n);
    }
    if (a.object) check_unique(*a.object, path + "/" + a.name);
  }
}

int count_keys(const ObjectSchema& s) {
  int n = 0;
  for (const KeySchema& k : s.keys) n += 1 + (k.object ? count_keys(*k.object) : 0);
  return n;
}

}  // namespace

TEST_CASE("the schema declares no key twice for one mode", "[schema]") {
  const ObjectSchema schema = latsim::run::scenario_schema();
  check_unique(schema, "");
  // Every section and every pipeline's keys are there (a count well above the top-level keys).
  CHECK(count_keys(schema) > 150);
  for (const char* section : {"motion", "tracker", "transport", "host", "display", "scene", "probes", "output",
                              "frames", "pipeline"})
    CHECK(schema.find(section) != nullptr);
}

TEST_CASE("every key of every shipped scenario has exactly one declaration", "[schema]") {
  const ObjectSchema schema = latsim::run::scenario_schema();
  int scenarios = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(LATSIM_SOURCE_DIR "/scenarios")) {
    const std::string file = entry.path().string();
    // base.json files are halves of scenarios, checked through the files that include them.
    if (entry.path().extension() != ".json" || file.find("/sweeps/") != std::string::npos ||
        entry.path().filename() == "base.json")
      continue;
    INFO(file);
    // A sweep file (a base scenario and axes) is not a scenario, wherever it lives.
    std::ifstream in(entry.path());
    if (nlohmann::json::parse(in).contains("axes")) continue;
    const auto doc = latsim::run::load_scenario(entry.path(), {});
    latsim::run::validate_scenario(doc);
    walk(doc.resolved(), schema, "");
    ++scenarios;
  }
  CHECK(scenarios >= 20);
}
