// One-line progress displays on stderr: for long batches of runs, and for one
// long run.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

#include "latsim/run/runner.hpp"

namespace latsim::sweep {

/// Shows "label: done/total runs, rate, ETA" on stderr, redrawn in place at
/// most a few times a second; silent unless stderr is a terminal, so logs and
/// pipes stay clean. Thread-safe: workers call advance() as runs finish, and
/// it costs them an atomic increment (and, on a terminal, a clock read):
/// whichever worker finds a redraw due draws, the others never wait for it.
class ProgressLine {
 public:
  ProgressLine(std::string label, size_t total, size_t already_done = 0);
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// Runs found finished before any ran (before the first advance()).
  void resume(size_t already_done);
  /// One more run finished.
  void advance();
  /// Draws the final state and ends the line.
  void finish();

 private:
  void draw(bool final_line);

  std::string label_;
  size_t total_;
  size_t resumed_;
  std::atomic<size_t> done_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  std::atomic<int64_t> next_draw_ns_;  ///< steady clock time of the next redraw
  std::mutex draw_mutex_;
};

/// Shows "run: simulated 12.3 s of 1000 s (1.2 %), 3.4 M events/s, ETA 14 min"
/// on stderr for a run that has taken more than a couple of seconds, redrawn
/// in place a few times a second; silent unless stderr is a terminal. With
/// `forced` it also reports from the start, and into a log one line per report.
/// finish() clears it, so the run's own output follows cleanly.
class SimulationProgress {
 public:
  explicit SimulationProgress(bool forced = false);
  SimulationProgress(const SimulationProgress&) = delete;
  SimulationProgress& operator=(const SimulationProgress&) = delete;
  ~SimulationProgress() { finish(); }

  /// For RunOptions::progress (called from the simulation's thread).
  void update(const run::RunProgress& progress);
  void finish();

  /// The line for `progress` after `elapsed_s` of wall time (no control characters).
  static std::string line(const run::RunProgress& progress, double elapsed_s);

 private:
  bool terminal_;
  bool enabled_;
  bool forced_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace latsim::sweep
