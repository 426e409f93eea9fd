// SIGINT and SIGTERM as a request to stop cleanly: work ends at its next
// check of the flag, children are ended with their parent, temporaries are
// removed, and the program says so in one line.
#pragma once

#include <atomic>
#include <chrono>
#include <string>
#include <sys/types.h>

namespace latsim::app {

/// Catches SIGINT and SIGTERM while it lives; main() makes the one of the
/// process, for every command. The first signal sets flag() (a run watching
/// it stops before its next event), is passed on to the children
/// (add_child), and starts a deadline: a command that has not ended by then
/// (a phase that cannot look at the flag) is ended by a watchdog thread,
/// which removes the registered temporaries (io/temporaries.hpp), says so in
/// one line and exits with exit_code(). A second signal ends the program at
/// once by the signal's default action, for a user who will not wait.
/// Signal handlers can only reach static storage: one per process.
class StopSignals {
 public:
  /// `command` names the program in the watchdog's line ("latsim optimise").
  explicit StopSignals(std::string command);
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  /// The process's one (main's); StopSignals must have been made.
  static StopSignals& installed();

  const std::atomic<bool>& flag() const;
  bool requested() const { return flag().load(); }
  /// "SIGINT" or "SIGTERM" (the first that arrived), or "" when none did.
  const char* name() const;
  /// 128 + the signal's number (130, 143): what a shell reports for a
  /// program the signal ended.
  int exit_code() const;

  /// A child process that a stop request is passed on to while it runs
  /// (one at a time); remove_child once it has been waited for.
  static void add_child(pid_t pid);
  static void remove_child();

  /// True for the first caller only: the stop is said in one line, by the
  /// command that stopped or by the watchdog that ended it, never by both
  /// (they can race when the command stops just as the deadline passes).
  static bool first_word();

  /// How long a command may take to stop after the first signal before the
  /// watchdog ends it: LATSIM_STOP_DEADLINE_MS when set (run_child sets a
  /// shorter one for its children, so that they end before their parent
  /// gives up on them), else 800 ms.
  static std::chrono::milliseconds deadline();
};

}  // namespace latsim::app
