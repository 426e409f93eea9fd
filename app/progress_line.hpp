// A one-line progress display on stderr for long batches of runs.
#pragma once

#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace latsim::app {

/// Shows "label: done/total runs, rate, ETA" on stderr, redrawn in place at
/// most a few times a second; silent unless stderr is a terminal, so logs and
/// pipes stay clean. Thread-safe: workers call advance() as runs finish.
class ProgressLine {
 public:
  ProgressLine(std::string label, size_t total, size_t already_done);
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// One more run finished.
  void advance();
  /// Draws the final state and ends the line.
  void finish();

 private:
  void draw(bool final_line);

  std::string label_;
  size_t total_;
  size_t resumed_;
  size_t done_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  std::mutex mutex_;
};

}  // namespace latsim::app
