// latsim: the command-line program. Parses, runs, writes; the work is in the libraries.
#include <cstdio>
#include <cstring>
#include <string>

#include "commands.hpp"
#include "latsim/run/runner.hpp"
#include "stop_signals.hpp"

namespace {

void print_usage(std::FILE* out) {
  std::fputs(
      "latsim - discrete-event simulation of motion-to-photon latency in HMD graphics pipelines\n"
      "\n"
      "usage: latsim <command> [options]    (latsim <command> --help for each command's options)\n"
      "\n"
      "commands:\n"
      "  run SCENARIO.json       run one scenario, write DIR/summary.json and friends\n"
      "  validate SCENARIO.json  check scenario files without running them\n"
      "  capacity SCENARIO.json  largest triangle count whose missed-field fraction stays within a threshold\n"
      "  sweep SWEEP.json        run a parameter sweep (parallel, resumable)\n"
      "  optimise SCENARIO.json  the setting of a pointer that minimises a figure within bounds on others\n"
      "  fidelity SCENARIO.json  what each step of simulation fidelity changes and costs\n"
      "  report DIR              tables and plots from a run or a sweep\n"
      "  compare CAPTURE RUN     a PresentMon capture beside a run: statistics, KS distances, CDFs\n"
      "  schema                  every scenario key: JSON Schema or Markdown reference\n"
      "  figures                 every figure a run may report: name, unit, meaning, headlines, columns\n"
      "\n"
      "exit codes: 0 success, 1 run failure, 2 bad input (nothing written)\n",
      out);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace latsim::app;
  if (argc < 2) {
    print_usage(stderr);
    return kExitBadInput;
  }
  const std::string cmd = argv[1];
  if (cmd == "--help" || cmd == "-h" || cmd == "help") {
    print_usage(stdout);
    return kExitOk;
  }
  if (cmd == "--version") {
    std::printf("latsim %s (%s)\n", latsim::run::latsim_version().c_str(), latsim::run::latsim_git_revision().c_str());
    return kExitOk;
  }
  // Every command, whatever phase it is in, answers SIGINT and SIGTERM
  // within StopSignals::deadline(); those that watch the flag sooner.
  const StopSignals signals("latsim " + cmd);
  // Each command sees its own name as argv[0].
  if (cmd == "run") return command_run(argc - 1, argv + 1);
  if (cmd == "validate") return command_validate(argc - 1, argv + 1);
  if (cmd == "capacity") return command_capacity(argc - 1, argv + 1);
  if (cmd == "sweep") return command_sweep(argc - 1, argv + 1);
  if (cmd == "optimise" || cmd == "optimize") return command_optimise(argc - 1, argv + 1);
  if (cmd == "fidelity") return command_fidelity(argc - 1, argv + 1);
  if (cmd == "report") return command_report(argc - 1, argv + 1);
  if (cmd == "compare") return command_compare(argc - 1, argv + 1);
  if (cmd == "schema") return command_schema(argc - 1, argv + 1);
  if (cmd == "figures") return command_figures(argc - 1, argv + 1);
  std::fprintf(stderr, "latsim: unknown command \"%s\" (try latsim --help)\n", cmd.c_str());
  return kExitBadInput;
}
