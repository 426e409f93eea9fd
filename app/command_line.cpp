// Option parsing, the recorded command line and the one-line messages shared by the subcommands.
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "latsim/scenario/readable.hpp"

namespace latsim::app {

namespace {

// The text of a number option as given, read whole: decimal digits (a sign
// where it may have one), in range, not rounded to 0. The parser alone took
// "-1" for an unsigned 18446744073709551615, "" for 0 and 1e-400 (a
// --max-events of 0: no limit) without a word.
CLI::Validator number_text_check(const std::string& type) {
  const bool is_float = type.rfind("FLOAT", 0) == 0, is_unsigned = type.rfind("UINT", 0) == 0;
  return CLI::Validator(
      [is_float, is_unsigned](std::string& text) -> std::string {
        const char* s = text.c_str();
        char* end = nullptr;
        errno = 0;
        bool ok = !text.empty() && !std::isspace(static_cast<unsigned char>(text[0]));
        if (is_float) {
          const double v = std::strtod(s, &end);
          ok = ok && errno != ERANGE && std::isfinite(v);
        } else {
          const bool digits = text.find_first_not_of(is_unsigned ? "0123456789" : "-0123456789") == std::string::npos;
          if (is_unsigned) std::strtoull(s, &end, 10);
          else std::strtoll(s, &end, 10);
          ok = ok && digits && errno != ERANGE;
        }
        ok = ok && end == s + text.size();
        if (ok) return "";
        const char* expected = is_float      ? "expected a finite number within a double's range"
                               : is_unsigned ? "expected an integer from 0 to 18446744073709551615"
                                             : "expected an integer from -9223372036854775808 to 9223372036854775807";
        return std::string(expected) + ", got " + scenario::quote_value(text);
      },
      "");
}

// Every number option of `app` and its subcommands is checked as above.
void check_number_options(CLI::App& app) {
  for (CLI::Option* opt : app.get_options()) {
    const std::string type = opt->get_type_name();
    if (type.rfind("UINT", 0) == 0 || type.rfind("INT", 0) == 0 || type.rfind("FLOAT", 0) == 0)
      opt->check(number_text_check(type));
  }
  for (CLI::App* sub : app.get_subcommands({})) check_number_options(*sub);
}

}  // namespace

std::optional<int> parse_options(CLI::App& app, int argc, char** argv) {
  check_number_options(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version print what they were asked for.
    if (e.get_exit_code() == 0) return app.exit(e) == 0 ? kExitOk : kExitBadInput;
    // A usage error is one line, like every other error: what it quotes of
    // the command line is cut and its control characters escaped, and the
    // whole line, with the hint after it, stays within kMessageChars.
    const std::string hint = " (" + app.get_name() + " --help lists the options)";
    std::cerr << scenario::readable(app.get_name() + ": " + e.what(), scenario::kMessageChars - hint.size() - 20)
              << hint << "\n";
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
  // A name the file system cannot hold fails only when the results are
  // written, after all the work (a 3,000-character --out: exit 1 at the end).
  if (out_dir.size() >= PATH_MAX)
    return scenario::quote_value(out_dir) + " is longer than a path may be (" + std::to_string(PATH_MAX - 1) +
           " bytes)";
  for (const auto& part : fs::path(out_dir))
    if (part.native().size() > NAME_MAX)
      return scenario::quote_value(out_dir) + " has a name longer than a file name may be (" + std::to_string(NAME_MAX) +
             " bytes)";
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
