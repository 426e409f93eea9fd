// Fuzz target: the option values of the commands whose checks are library
// functions: --set (an override applied to a shipped scenario, which is then
// validated as run and validate check it before work), fidelity's --vary,
// optimise's --constraint and sweep's --shard. One input is lines, each one
// option value given to every parser. Bad values must end as the exception
// each documents (ScenarioError, std::invalid_argument) or nullopt; anything
// else escaping, a crash or a hang is a finding. (The CLI11 parse and the
// checks in app/ sit inside each command's function, which goes on to work:
// they are covered by tests/cli/hardening.sh, not here.)
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>

#include "fuzz_inputs.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/sweep/fidelity_table.hpp"
#include "latsim/sweep/optimise.hpp"
#include "latsim/sweep/shard.hpp"

namespace {

void one_value(const std::string& text) {
  try {
    const auto doc = latsim::run::load_scenario(latsim::fuzz::mirror_dir() / "hmd_60hz_direct.json", {text});
    (void)latsim::run::validate_scenario(doc);
  } catch (const latsim::scenario::ScenarioError&) {
  }
  try {
    const auto axis = latsim::sweep::parse_vary(text);
    if (axis.pointer.empty() || axis.values.empty()) std::abort();
  } catch (const std::invalid_argument&) {
  }
  if (const auto bound = latsim::sweep::parse_bound(text))
    if (bound->figure.empty() || std::isnan(bound->bound)) std::abort();
  try {
    const auto env = [&text](const std::string&) -> std::optional<std::string> { return text; };
    const auto shard = latsim::sweep::parse_shard(text, env);
    if (shard.count == 0 || shard.index >= shard.count) std::abort();
  } catch (const std::invalid_argument&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  // At most 8 values an input: each is a scenario validated.
  size_t start = 0;
  for (int n = 0; n < 8 && start <= input.size(); ++n) {
    const size_t end = std::min(input.find('\n', start), input.size());
    one_value(std::string(input.substr(start, end - start)));
    start = end + 1;
  }
  return 0;
}
