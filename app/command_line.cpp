// Option parsing, the recorded command line and the one-line messages shared by the subcommands.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
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
    // A usage error is one line, like every other error: what it quotes of
    // the command line is cut and its control characters escaped.
    std::cerr << scenario::readable(app.get_name() + ": " + e.what()) << " (" << app.get_name()
              << " --help lists the options)\n";
    return kExitBadInput;
  }
  return std::nullopt;
}

CLI::Validator non_negative_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v) || v < 0)
          return "must be a finite number of 0 or more, got " + scenario::quote_value(text);
        return "";
      },
      "NUMBER >= 0");
}

void add_max_events_option(CLI::App& app, double& max_events) {
  app.add_option("--max-events", max_events,
                 "refuse a run whose estimated event count is above this (the estimate names the key that drives "
                 "it; 0: no limit)")
      ->check(non_negative_number())
      ->capture_default_str();
}

std::optional<std::string> out_dir_problem(const std::string& out_dir) {
  namespace fs = std::filesystem;
  if (out_dir.empty()) return "must name a directory";
  if (out_dir.find('\0') != std::string::npos) return "contains a NUL character";
  std::error_code ec;
  const auto st = fs::status(out_dir, ec);
  if (fs::exists(st) && !fs::is_directory(st)) return scenario::quote_value(out_dir) + " exists and is not a directory";
  // The nearest part of the path that exists must be a directory to make the rest in.
  for (fs::path up = fs::absolute(out_dir, ec).parent_path(); !ec && !up.empty(); up = up.parent_path()) {
    std::error_code missing;
    const auto above = fs::status(up, missing);
    if (fs::exists(above))
      return fs::is_directory(above) ? std::nullopt
                                     : std::optional<std::string>(scenario::quote_value(out_dir) + " lies under " +
                                                                  scenario::quote_value(up.string()) +
                                                                  ", which is not a directory");
    if (up == up.root_path()) break;
  }
  return std::nullopt;
}

std::optional<int> refuse_out_dir(const std::string& command, const std::string& out_dir) {
  const auto problem = out_dir_problem(out_dir);
  if (!problem) return std::nullopt;
  std::fprintf(stderr, "%s: --out %s\n", command.c_str(), problem->c_str());
  return kExitBadInput;
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
