// Fuzz target: a sweep file as `latsim sweep` and `latsim validate` read it
// (axes, ranges, zips, the base scenario and its resolution at every point).
// Bad input must end as a SweepError; anything else escaping, a crash or a
// hang is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_inputs.hpp"
#include "latsim/run/prepared_run.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/scenario/json_text.hpp"
#include "latsim/sweep/plan.hpp"

namespace {

using Json = nlohmann::json;

// As the sweep command resolves a point: the runner's resolved scenario.
Json resolve(const Json& scenario, const std::filesystem::path& base_dir) {
  auto doc = latsim::scenario::ScenarioDocument::from_json(scenario, base_dir);
  return latsim::run::PreparedRun(doc, latsim::run::RunOptions{}).resolved();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // The base scenario is named relative to the sweep file, which "lives" in
  // the mirror of the shipped scenarios' sweeps/ directory.
  const auto sweep_file = latsim::fuzz::mirror_dir() / "sweeps" / "input.json";
  try {
    const Json sweep = latsim::scenario::parse_json(
        std::string_view(reinterpret_cast<const char*>(data), size), sweep_file.string());
    const auto plan = latsim::sweep::SweepPlan::from_json(sweep, sweep_file, resolve);
    (void)plan.to_json();
  } catch (const latsim::scenario::ScenarioError&) {
  } catch (const latsim::sweep::SweepError&) {
  }
  return 0;
}
