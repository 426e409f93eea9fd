// Option parsing shared by every subcommand.
#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace latsim::app {

std::optional<int> parse_options(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitBadInput;
  }
  return std::nullopt;
}

}  // namespace latsim::app
