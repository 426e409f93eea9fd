// latsim report: tables and plots from a result directory, drawn by the
// Python analysis (which reads only result files).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "child_process.hpp"
#include "commands.hpp"
#include "stop_signals.hpp"

namespace latsim::app {

int command_report(int argc, char** argv) {
  CLI::App app{"Writes report.md, latency_table.csv and plots (CDF, histogram, sweep axes, Gantt charts) for a run "
               "directory, a sweep directory or a directory of run directories",
               "latsim report"};
  std::string dir;
  int gantt_limit = -1;
  int top = -1;
  std::string figure;
  app.add_option("dir", dir, "result directory")->required();
  app.add_option("--gantt-limit", gantt_limit,
                 "draw at most this many Gantt charts (default: a sweep's 6, one per point evenly spaced; "
                 "otherwise every run with a timeline)")
      ->check(non_negative_number());
  app.add_option("--top", top,
                 "a sweep's table in report.md: this many lowest and highest points (default 10; 0: every point); "
                 "latency_table.csv always has every point")
      ->check(non_negative_number());
  app.add_option("--figure", figure,
                 "the column a sweep's table is sorted by and its heat map shows (default: the mean of the figure "
                 "the runs' pipelines declare first, rotation_latency_mean_ms behind a time warp, else mtp_mean_ms; "
                 "e.g. mtp_p99_ms, registration_error_mean_arcmin)");
  std::string figures;
  app.add_option("--figures", figures,
                 "the columns of report.md's tables and the figures of the sweep plots, comma-separated (e.g. "
                 "rotation_latency_mean_ms,mtp_p99_ms,missed_refreshes; default: the sweep file's \"figures\", else "
                 "the pipelines' headline first)");
  std::string title;
  app.add_option("--title", title, "the report's title (default: the directory's name)");
  if (const auto rc = parse_options(app, argc, argv)) return *rc;
  if (!std::filesystem::is_directory(dir)) {
    std::cerr << dir << ": not a directory\n";
    return kExitBadInput;
  }
  try {
    std::vector<std::string> command{python_interpreter(), analysis_script("report.py").string(), dir};
    if (gantt_limit >= 0) command.insert(command.end(), {"--gantt-limit", std::to_string(gantt_limit)});
    if (top >= 0) command.insert(command.end(), {"--top", std::to_string(top)});
    if (!figure.empty()) command.insert(command.end(), {"--figure", figure});
    if (!title.empty()) command.insert(command.end(), {"--title", title});
    if (!figures.empty()) command.insert(command.end(), {"--figures", figures});
    const ChildResult child = run_child(command);
    // The script's own codes already follow the program's (0 ok, 1 cannot
    // write, 2 bad input, 130 and 143 stopped) and it has said why in one line.
    if (child.exit_code == kExitOk || child.exit_code == kExitFailure || child.exit_code == kExitBadInput ||
        child.exit_code == 130 || child.exit_code == 143)
      return child.exit_code;
    if (StopSignals::installed().requested()) {
      if (StopSignals::first_word()) std::cerr << "report: stopped by " << StopSignals::installed().name() << "\n";
      return StopSignals::installed().exit_code();
    }
    std::cerr << "report: the analysis script failed (exit status " << child.exit_code << ")\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "report: " << e.what() << "\n";
    return kExitFailure;
  }
}

}  // namespace latsim::app
