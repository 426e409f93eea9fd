// The figure registry (results/figure_registry.json) declares every figure
// once. A figure a run reports that the registry does not declare, or
// declares for another pipeline, fails here naming it; so does a declared
// figure that no shipped scenario (nor a case of this test) produces. The
// registry's own rules (unique names, known families and headlines, column
// orders without gaps) are checked as it is read.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "latsim/results/figure_registry.hpp"
#include "latsim/run/builtin_pipelines.hpp"
#include "run_helpers.hpp"

using namespace latsim;
using Json = nlohmann::json;
using results::FigureDecl;
using results::FigureRegistry;
namespace fs = std::filesystem;

namespace {

const FigureRegistry& registry() { return FigureRegistry::builtin(); }

// A registry of one figure besides a headline, for the rules of reading one.
std::string one_figure(const std::string& figure, const std::string& more = "") {
  return R"({"families": {"pipeline": {"glossary": false}}, "headlines": {"default": {"used_by": "all"}},)" + more +
         R"("figures": [{"name": "a_ms", "kind": "number", "unit": "ms", "family": "pipeline", "pipelines": "all",
                          "meaning": "a", "headline": {"default": 1}}, )" +
         figure + "]}";
}

std::string parse_error(const std::string& text) {
  try {
    (void)FigureRegistry::parse(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

/// What the runs produced: per declared figure, the pipelines that reported it.
struct Produced {
  std::map<const FigureDecl*, std::set<std::string>> by;
  std::vector<std::string> problems;
  std::set<std::string> paths;  // every declared name a run reported, as reported

  // Walks a run's figures: every leaf, empty container and distribution must
  // be a declared figure; containers without a declaration of their own hold
  // declared figures.
  void walk(const Json& node, const std::string& path, const std::string& pipeline, const std::string& run) {
    const FigureDecl* d = path.empty() ? nullptr : registry().find(path);
    if (d != nullptr) {
      by[d].insert(pipeline);
      paths.insert(path);
      if (!d->produced_by(pipeline))
        problems.push_back(run + ": figure \"" + path + "\" is declared in results/figure_registry.json for " +
                           "other pipelines than " + pipeline + " (add it to its \"pipelines\")");
    }
    const bool distribution = node.is_object() && node.contains("count") && node.contains("histogram");
    if (d != nullptr && (distribution || !node.is_structured())) return;
    if (d == nullptr && (distribution || !node.is_structured() || node.empty())) {
      problems.push_back(run + ": figure \"" + path + "\" (" + pipeline +
                         ") is not declared in results/figure_registry.json (docs/adding-a-figure.md)");
      return;
    }
    if (node.is_object())
      for (auto it = node.begin(); it != node.end(); ++it)
        walk(it.value(), path.empty() ? it.key() : path + "." + it.key(), pipeline, run);
    if (node.is_array())
      for (size_t i = 0; i < node.size(); ++i) walk(node[i], path + "." + std::to_string(i), pipeline, run);
  }

  /// The figures of one run; a figure it reports that the registry refuses
  /// ends the run, and is a problem here like any other.
  template <class RunIt>
  void add(RunIt&& run_it, const std::string& run) {
    try {
      const Json summary = run_it();
      walk(summary.at("figures"), "", summary.at("scenario").at("pipeline").at("type").get<std::string>(), run);
    } catch (const std::logic_error& e) {
      problems.push_back(run + ": " + e.what());
    }
  }
};

/// Runs a shipped scenario with overrides in-process.
auto run_file(const fs::path& file, std::vector<std::string> overrides, run::RunOptions options = {}) {
  return [=] { return run::run_scenario(run::load_scenario(file.string(), overrides), options); };
}

}  // namespace

TEST_CASE("the registry is read with its rules", "[figures]") {
  CHECK(parse_error(one_figure(R"({"name": "b", "kind": "number", "unit": "", "family": "pipeline", "pipelines": "all",
                                   "meaning": "b"})")) == "");
  // A name declared twice, an unknown family, kind, headline or placeholder, no meaning.
  CHECK_THAT(parse_error(one_figure(R"({"name": "a_ms", "kind": "number", "unit": "ms", "family": "pipeline",
                                        "pipelines": "all", "meaning": "again"})")),
             Catch::Contains("figure a_ms: is declared twice"));
  CHECK_THAT(parse_error(one_figure(R"({"name": "b", "kind": "number", "unit": "", "family": "recorder",
                                        "pipelines": "all", "meaning": "b"})")),
             Catch::Contains("figure b: family \"recorder\""));
  CHECK_THAT(parse_error(one_figure(R"({"name": "b", "kind": "histogram", "unit": "", "family": "pipeline",
                                        "pipelines": "all", "meaning": "b"})")),
             Catch::Contains("(b): unknown kind \"histogram\""));
  CHECK_THAT(parse_error(one_figure(R"({"name": "b", "kind": "number", "unit": "", "family": "pipeline",
                                        "pipelines": "all", "meaning": "b", "headline": {"warp": 2}})")),
             Catch::Contains("figure b: headline set \"warp\""));
  CHECK_THAT(parse_error(one_figure(R"({"name": "b_<eye>", "kind": "number", "unit": "", "family": "pipeline",
                                        "pipelines": "all", "meaning": "b"})")),
             Catch::Contains("figure b_<eye>: placeholder <eye>"));
  CHECK_THAT(parse_error(one_figure(R"({"name": "b", "kind": "number", "unit": "", "family": "pipeline",
                                        "pipelines": "all", "meaning": ""})")),
             Catch::Contains("(b): says nothing of what it means"));
  // Two figures at one headline rank, columns with a gap.
  CHECK_THAT(parse_error(one_figure(R"({"name": "b", "kind": "number", "unit": "", "family": "pipeline",
                                        "pipelines": "all", "meaning": "b", "headline": {"default": 1}})")),
             Catch::Contains("headline default: rank 1 is given twice"));
  CHECK_THAT(parse_error(one_figure(R"({"name": "b", "kind": "number", "unit": "", "family": "pipeline",
                                        "pipelines": "all", "meaning": "b",
                                        "columns": [{"order": 2, "name": "b", "figure": "b", "label": "b"}]})")),
             Catch::Contains("column b: orders run 1, 2, 3"));
}

TEST_CASE("names with placeholders and groups find their declaration", "[figures]") {
  const auto name_of = [](std::string_view n) {
    const FigureDecl* d = registry().find(n);
    return d == nullptr ? std::string("none") : d->name;
  };
  CHECK(name_of("motion_to_photon_ms") == "motion_to_photon_ms");
  CHECK(name_of("memories.0.renders") == "memories.<n>.renders");
  CHECK(name_of("memories.12.renders") == "memories.<n>.renders");
  CHECK(name_of("memories.x.renders") == "none");
  CHECK(name_of("translation_latency_memory3_ms") == "translation_latency_memory<n>_ms");
  CHECK(name_of("translation_latency_memory_ms") == "none");
  CHECK(name_of("registration_error_arcmin_onset") == "registration_error_arcmin_<phase>");
  CHECK(name_of("registration_error_arcmin_onsets") == "none");
  CHECK(name_of("stage_ms.TRANSFORM") == "stage_ms.<stage>");
  // A group holds figures declared on their own: another configuration's, the window's.
  CHECK(name_of("variants.1.render_load") == "render_load");
  CHECK(name_of("variants.0.memories.3.renders") == "memories.<n>.renders");
  CHECK(name_of("variants.0.window.memories.1.drawn") == "memories.<n>.drawn");
  CHECK(name_of("window.render_load") == "render_load");
  CHECK(name_of("variants.0.configuration") == "variants.<n>.configuration");
  CHECK(name_of("variants.0") == "none");
  CHECK(name_of("variants.0.nonsense") == "none");
}

TEST_CASE("the registry names registered pipelines and orders its columns", "[figures]") {
  const std::vector<std::string> names = run::builtin_pipelines().names();
  for (const FigureDecl& d : registry().figures())
    for (const std::string& p : d.pipelines) {
      INFO(d.name);
      CHECK(std::find(names.begin(), names.end(), p) != names.end());
    }
  // The results tables' columns, one per figure statistic, numbered from 1.
  const auto& columns = registry().columns();
  REQUIRE_FALSE(columns.empty());
  for (size_t i = 0; i < columns.size(); ++i) CHECK(columns[i].order == static_cast<int>(i) + 1);
  CHECK(columns.front().name == "mtp_mean_ms");
  CHECK(columns.front().figure == "motion_to_photon_ms.mean");
}

TEST_CASE("every figure a run reports is declared, and every declared figure is reported", "[figures]") {
  Produced produced;
  for (const fs::path& file : testing::shipped_scenarios()) produced.add(run_file(file, {"/duration_s=2"}), file.string());
  // Figures no shipped scenario reports in two seconds: the cases that do.
  const fs::path s = LATSIM_SOURCE_DIR "/scenarios";
  // The window of position_window_s (gallery_experiment's ends at 30 s).
  produced.add(run_file(s / "arp/gallery_experiment.json", {"/duration_s=2", "/pipeline/position_window_s=[0.5,1.5]"}),
               "gallery_experiment with a window");
  // A serial line in interrupt mode whose handlers cost time.
  produced.add(run_file(s / "hmd_60hz_serial_interrupt.json", {"/duration_s=1", "/transport/per_char_interrupt_us=20"}),
               "serial interrupt with handlers");
  // Frameless rendering whose fallback the head's turn triggers.
  produced.add(run_file(s / "frameless/side_by_side.json", {"/duration_s=1", "/pipeline/fallback/trigger_deg=0.1"}),
               "frameless with fallbacks");
  // A capture of a warped image, in a run directory (frames.<n>.files lists its images, not written here).
  run::RunOptions written;
  written.out_dir = LATSIM_BINARY_DIR "/tests/figure_registry_run";
  written.write_images = false;
  fs::remove_all(written.out_dir);
  produced.add(run_file(s / "modern/timewarp_frames.json", {"/duration_s=1.05", "/frames/at_s=[1.0]"}, written),
               "timewarp_frames with a capture at 1 s");
  fs::remove_all(written.out_dir);
  for (const std::string& p : produced.problems) FAIL_CHECK(p);

  for (const FigureDecl& d : registry().figures()) {
    if (d.kind == "summary") continue;  // summary.json's, not figures.json's
    if (d.kind == "group") {
      const bool used = std::any_of(produced.paths.begin(), produced.paths.end(), [&](const std::string& path) {
        for (size_t dot = path.find('.'); dot != std::string::npos; dot = path.find('.', dot + 1))
          if (registry().matches(d.name, path.substr(0, dot))) return true;
        return false;
      });
      if (!used) FAIL_CHECK("group \"" + d.name + "\" is declared in results/figure_registry.json but holds nothing any run reports");
      continue;
    }
    const auto it = produced.by.find(&d);
    if (it == produced.by.end()) {
      FAIL_CHECK("figure \"" + d.name + "\" is declared in results/figure_registry.json but no shipped scenario " +
                 "(nor a case of this test) reports it");
      continue;
    }
    for (const std::string& p : d.pipelines)
      if (it->second.count(p) == 0)
        FAIL_CHECK("figure \"" + d.name + "\" is declared for " + p + " but no run of " + p + " reports it");
  }
}
