// Option parsing, the recorded command line and the one-line messages shared by the subcommands.
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "latsim/scenario/readable.hpp"

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

std::vector<std::string> command_line_of(int argc, char** argv) {
  std::vector<std::string> out{"latsim"};
  for (int i = 0; i < argc; ++i) out.emplace_back(argv[i]);
  return out;
}

// One line on stderr: the file, the JSON pointer and what is wrong.
int bad_input(const std::string& file, const scenario::ScenarioError& e) {
  std::fprintf(stderr, "%s\n", e.line(file).c_str());
  return kExitBadInput;
}

// Legal but doubtful input, one line each on stderr.
void print_warnings(const std::string& file, const std::vector<std::string>& warnings) {
  const std::string name = scenario::readable(file, 2 * scenario::kQuotedChars);
  for (const auto& w : warnings) std::fprintf(stderr, "%s: warning: %s\n", name.c_str(), scenario::readable(w).c_str());
}

}  // namespace latsim::app
