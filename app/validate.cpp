// latsim validate: scenario and sweep files checked without running them.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"
#include "stop_signals.hpp"
#include "latsim/run/prepared_run.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/sweep/common.hpp"

namespace latsim::app {

int command_validate(int argc, char** argv) {
  CLI::App app{"Check scenario and sweep files without running them", "latsim validate"};
  std::vector<std::string> files;
  std::vector<std::string> sets;
  bool resolved = false;
  double max_events = run::kDefaultMaxEvents;
  app.add_option("files", files, "scenario or sweep JSON files")->required();
  app.add_option("--set", sets, "override a value: /json/pointer=value (repeatable; scenarios only)");
  app.add_flag("--resolved", resolved, "print each scenario as it would run (every default applied) instead of ok");
  add_max_events_option(app, max_events);
  if (const auto rc = parse_options(app, argc, argv)) return *rc;
  int rc = kExitOk;
  const StopSignals& signals = StopSignals::installed();
  for (const auto& file : files) {
    if (signals.requested()) break;
    const std::string name = scenario::readable(file, 2 * scenario::kQuotedChars);
    try {
      if (sweep::is_sweep_file(file)) {
        rc = std::max(rc, sweep::validate_sweep(file, max_events, &signals.flag()));
        continue;
      }
      const auto doc = run::load_scenario(file, sets);
      run::RunOptions options;
      options.max_events = max_events;
      const run::PreparedRun prepared(doc, options);  // built once: its warnings and its resolved scenario
      print_warnings(file, prepared.warnings());
      if (resolved) std::printf("%s\n", prepared.resolved().dump(2, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
      else std::printf("%s: ok\n", name.c_str());
    } catch (const scenario::ScenarioError& e) {
      rc = bad_input(file, e);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", name.c_str(), scenario::readable(e.what()).c_str());
      rc = kExitBadInput;
    }
  }
  // A sweep's points are built until a stop request; a scenario, whose build
  // looks at no flag, is ended by StopSignals' watchdog.
  if (signals.requested()) {
    if (StopSignals::first_word()) std::fprintf(stderr, "validate: stopped by %s; nothing written\n", signals.name());
    return signals.exit_code();
  }
  return rc;
}

}  // namespace latsim::app
