#include "latsim/sweep/sweep_file.hpp"

#include <limits>

#include "latsim/scenario/config.hpp"
#include "latsim/sweep/plan.hpp"
#include "latsim/sweep/run_table.hpp"

namespace latsim::sweep {

namespace {

using Json = nlohmann::json;

// Plans past this size are almost certainly a typo in a range step.
constexpr double kMaxReplications = 1'000'000;

void bind_axis(scenario::Section& a, SweepFileAxis& x) {
  a.doc("One swept parameter: a JSON pointer into the scenario and the values it takes.");
  a.text("pointer", x.pointer,
         {.required = true, .doc = "where in the scenario the value goes, such as \"/display/refresh_hz\""});
  a.value("values", x.values, {.doc = "the values, in order (or \"range\")"});
  a.value("range", x.range, {.doc = "{\"from\": a, \"to\": b, \"step\": s}, both ends included (or \"values\")"});
  a.text("label", x.label, {.doc = "what tables and plots call the axis (default: its pointer)"});
  if (a.describing()) return;
  a.check("pointer", !x.pointer.empty() && x.pointer[0] == '/',
          "\"" + x.pointer + "\" is not a JSON pointer (it must start with /)");
  a.check("label", !a.has("label") || (!x.label.empty() && x.label.size() <= 200),
          "expected a name of 1 to 200 characters for tables and plots");
  a.check("", a.has("values") != a.has("range"), "give exactly one of \"values\" and \"range\"");
  a.check("values", !a.has("values") || (x.values.is_array() && !x.values.empty()),
          "expected a non-empty array of values");
}

}  // namespace

void bind(scenario::Section& s, SweepFile& f) {
  s.doc("A parameter sweep: a base scenario, axes of values at JSON pointers, and replications of every point.");
  s.text("description", f.description, {.doc = "what the sweep is for"});
  s.text("base", f.base, {.required = true, .doc = "the path of the base scenario, relative to the sweep file"});
  if (!s.describing() && !s.has("axes"))
    s.fail("axes", "expected an array of axes ([] for replications of the base scenario alone)");
  s.objects("axes", f.axes, bind_axis, {.required = true, .doc = "the swept parameters"});
  s.choice("mode", f.mode, {{"cartesian", SweepFile::Mode::cartesian}, {"zip", SweepFile::Mode::zip}},
           {.doc = "cartesian: every combination (the last axis varies fastest); zip: the i-th value of every axis"});
  s.integer("replications", f.replications,
            {.min = 1.0, .max = kMaxReplications, .doc = "runs of every point, each with its own random streams"});
  s.value("seed", f.seed, {.doc = "the seed of every run (default: the base scenario's)"});
  s.value("overrides", f.overrides, {.doc = "{\"/json/pointer\": value} applied to the base scenario first"});
  s.text("keep", f.keep, {.doc = "which runs keep their traces: \"figures\", \"first\", \"all\" or \"runs=I,J,...\""});
  s.choices("figures", f.figures, choosable_figures(),
            {.doc = "the report's columns: results.csv column names, or any figure by its figures.json path "
                    "(frames_missed, motion_to_photon_ms.p99), which then get results.csv columns too"});
  if (s.describing()) return;
  const bool seed_ok = f.seed.is_null() || f.seed.is_number_unsigned() ||
                       (f.seed.is_number_integer() && f.seed.get<int64_t>() >= 0);
  s.check("seed", seed_ok,
          "expected an integer from 0 to " + std::to_string(std::numeric_limits<uint64_t>::max()));
  s.check("overrides", f.overrides.is_object(), "expected an object of {\"/json/pointer\": value}");
  s.check("figures", !s.has("figures") || !f.figures.empty(), "expected a non-empty array of results.csv column names or figure paths");
}

SweepFile read_sweep_file(const Json& sweep, const std::filesystem::path& file) {
  if (!sweep.is_object()) throw SweepError(file, "", "a sweep must be a JSON object");
  SweepFile f;
  try {
    const auto doc = scenario::ScenarioDocument::from_json(sweep, file.parent_path());
    scenario::Section root(doc.root());
    bind(root, f);
    doc.check_unknown_keys();
  } catch (const scenario::ScenarioError& e) {
    throw SweepError(file, e.pointer(), e.message());
  }
  return f;
}

}  // namespace latsim::sweep
