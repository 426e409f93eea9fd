// SIGINT and SIGTERM as a request to stop cleanly: runs end at their next
// event, temporaries are removed, and the program says so in one line.
#pragma once

#include <atomic>

namespace latsim::app {

/// Catches SIGINT and SIGTERM while it lives. The first signal sets flag()
/// (a run watching it stops before its next event); a second one ends the
/// program at once by the signal's default action, for a user who will not
/// wait. Signal handlers can only reach static storage, so the state is
/// per process: construct one at a time.
class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  const std::atomic<bool>& flag() const;
  bool requested() const { return flag().load(); }
  /// "SIGINT" or "SIGTERM" (the first that arrived), or "" when none did.
  const char* name() const;
  /// 128 + the signal's number (130, 143): what a shell reports for a
  /// program the signal ended.
  int exit_code() const;
};

}  // namespace latsim::app
