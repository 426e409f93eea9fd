// Fuzz target: a scenario file as `latsim validate` reads it (includes,
// resolution and every parameter check, models built but not run). Bad input
// must end as a ScenarioError; anything else escaping, a crash or a hang is a
// finding.
#include <cstddef>
#include <cstdint>

#include "fuzz_inputs.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto file = latsim::fuzz::write_input("input.json", data, size);
  try {
    const auto doc = latsim::run::load_scenario(file, {});
    (void)latsim::run::validate_scenario(doc);
  } catch (const latsim::scenario::ScenarioError&) {
    // Bad input, reported as the user would see it.
  }
  return 0;
}
