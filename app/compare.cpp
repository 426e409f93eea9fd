// latsim compare: a frame-timing capture beside a run, drawn by the Python
// analysis (analysis/compare.py, which reads only the two files).
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "child_process.hpp"
#include "commands.hpp"

namespace latsim::app {

int command_compare(int argc, char** argv) {
  CLI::App app{"Sets a PresentMon capture beside a run: frame interval, CPU busy, GPU busy and present-to-display "
               "latency, each as count, mean, p50, p99 and the two-sample Kolmogorov-Smirnov distance "
               "(compare.md, compare.csv) and as overlaid CDFs (compare_<column>.png)",
               "latsim compare"};
  std::string capture, run, out, application, process_id;
  app.add_option("capture", capture, "PresentMon CSV (current, v1 or v2 columns)")->required();
  app.add_option("run", run, "run directory (its presentmon.csv), or another capture CSV")->required();
  app.add_option("--out,-o", out, "output directory (default: RUN/compare)");
  app.add_option("--application", application, "the capture's process, by Application (when it holds several)");
  app.add_option("--process-id", process_id, "the capture's process, by ProcessID (when it holds several)");
  if (const auto rc = parse_options(app, argc, argv)) return *rc;
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(capture, ec)) {
    std::cerr << "compare: " << capture << ": not a regular file\n";
    return kExitBadInput;
  }
  if (fs::is_directory(run, ec) ? !fs::is_regular_file(fs::path(run) / "presentmon.csv", ec)
                                : !fs::is_regular_file(run, ec)) {
    std::cerr << "compare: " << run << ": neither a run directory with a presentmon.csv nor a capture file\n";
    return kExitBadInput;
  }
  try {
    std::vector<std::string> command{python_interpreter(), analysis_script("compare.py").string(), capture, run};
    if (!out.empty()) command.insert(command.end(), {"--out", out});
    if (!application.empty()) command.insert(command.end(), {"--application", application});
    if (!process_id.empty()) command.insert(command.end(), {"--process-id", process_id});
    const ChildResult child = run_child(command);
    // The script's codes follow the program's and it has said why in one line.
    if (child.exit_code == kExitOk || child.exit_code == kExitFailure || child.exit_code == kExitBadInput ||
        child.exit_code == 130)
      return child.exit_code;
    std::cerr << "compare: the analysis script failed (exit status " << child.exit_code << ")\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "compare: " << e.what() << "\n";
    return kExitFailure;
  }
}

}  // namespace latsim::app
