// Option parsing shared by every subcommand.
#include <iostream>

#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace latsim::app {

std::optional<int> parse_options(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version print what they were asked for.
    if (e.get_exit_code() == 0) return app.exit(e) == 0 ? kExitOk : kExitBadInput;
    // A usage error is one line, like every other error.
    std::cerr << app.get_name() << ": " << e.what() << " (" << app.get_name() << " --help lists the options)\n";
    return kExitBadInput;
  }
  return std::nullopt;
}

void add_max_events_option(CLI::App& app, double& max_events) {
  app.add_option("--max-events", max_events,
                 "refuse a run whose estimated event count is above this (the estimate names the key that drives "
                 "it; 0: no limit)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
}

}  // namespace latsim::app
