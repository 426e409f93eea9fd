// Running another program (latsim itself, python3) and measuring what it cost.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace latsim::app {

/// How a child process ended and what it used.
struct ChildResult {
  int exit_code = -1;       ///< the exit status, or 128 + signal number when killed
  double wall_s = 0.0;      ///< from spawn to exit
  double peak_rss_mb = 0.0; ///< the child's own ru_maxrss, from wait4
};

/// Runs argv[0] (searched on PATH when it has no slash) with argv, inheriting
/// stdin, stdout and stderr, and waits for it. The child is in a process
/// group of its own, is passed a stop request on (StopSignals::add_child) and
/// ends with its parent (SIGTERM when the parent dies, however it dies).
/// Throws std::runtime_error when it cannot be started.
ChildResult run_child(const std::vector<std::string>& argv);

/// The running program's own executable (/proc/self/exe).
std::filesystem::path self_executable();

/// The Python interpreter for the analysis scripts: /usr/bin/python3 when it
/// exists (the system one carries matplotlib), else python3 from PATH.
std::string python_interpreter();

/// analysis/<script>: in the source tree the program was built from, else
/// beside the executable (../analysis or analysis). Throws when not found.
std::filesystem::path analysis_script(const std::string& script);

}  // namespace latsim::app
