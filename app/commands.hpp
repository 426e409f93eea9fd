// The latsim command-line program's subcommands; each parses its own options.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "latsim/run/exit_codes.hpp"
#include "latsim/scenario/config.hpp"

namespace CLI {
class App;
class Validator;
}

namespace latsim::app {

/// Exit codes shared by every subcommand.
using run::kExitBadInput;
using run::kExitFailure;
using run::kExitOk;

/// Parses a subcommand's options: the exit code when the program should stop
/// here (help printed: 0; bad options, message printed: 2), nothing otherwise.
std::optional<int> parse_options(CLI::App& app, int argc, char** argv);

/// A finite number of 0 or more; refusing others in one line that quotes the
/// value as given (cut when long), never a bound such as DBL_MAX in full.
CLI::Validator non_negative_number();

/// --max-events N: the largest event estimate a run may have (run::RunOptions::max_events).
void add_max_events_option(CLI::App& app, double& max_events);

/// What is wrong with an output directory before any work starts, if
/// anything: empty, not a directory, or under something that is not one.
std::optional<std::string> out_dir_problem(const std::string& out_dir);
/// out_dir_problem as the command's one line ("latsim optimise: --out ...");
/// kExitBadInput when there is a problem.
std::optional<int> refuse_out_dir(const std::string& command, const std::string& out_dir);

/// The command line as summary.json records it: "latsim" and the subcommand's arguments.
std::vector<std::string> command_line_of(int argc, char** argv);
/// One line on stderr: the file, the JSON pointer and what is wrong; returns kExitBadInput.
int bad_input(const std::string& file, const scenario::ScenarioError& e);
/// Legal but doubtful input, one line each on stderr.
void print_warnings(const std::string& file, const std::vector<std::string>& warnings);

int command_run(int argc, char** argv);       ///< latsim run SCENARIO [--out DIR] [--seed N] [--set P=V]...
int command_validate(int argc, char** argv);  ///< latsim validate SCENARIO...
int command_capacity(int argc, char** argv);  ///< latsim capacity SCENARIO: largest triangle count within a missed-field threshold
int command_optimise(int argc, char** argv);  ///< latsim optimise SCENARIO --vary P=LO:HI --minimise FIGURE
int command_sweep(int argc, char** argv);     ///< latsim sweep SWEEP.json --out DIR [-j N]
int command_fidelity(int argc, char** argv);  ///< latsim fidelity SCENARIO --vary P=v1,v2 --metric NAME
int command_report(int argc, char** argv);    ///< latsim report DIR
int command_compare(int argc, char** argv);   ///< latsim compare CAPTURE RUN_DIR [--out DIR]
int command_schema(int argc, char** argv);    ///< latsim schema [--format json-schema|markdown]
int command_figures(int argc, char** argv);   ///< latsim figures [--format markdown|json]

}  // namespace latsim::app
