// A request from outside (a signal, a caller's interrupt) to stop the work in
// progress on this thread, for loops that run outside the event queue: the
// classification of head motion, apparent latency, writing results.
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>

namespace latsim::des {

/// Thrown by check_stop() when the calling thread's stop flag is set; the
/// runner turns it into "interrupted", never into a failure.
class StopRequested : public std::exception {
 public:
  const char* what() const noexcept override { return "stopped on request"; }
};

/// Makes `flag` the calling thread's stop flag while it lives (nullptr: none);
/// restores the one before. A run sets it for its whole length, so that any
/// long loop below it can answer a signal without being handed the flag.
class ScopedStopFlag {
 public:
  explicit ScopedStopFlag(const std::atomic<bool>* flag);
  ~ScopedStopFlag();
  ScopedStopFlag(const ScopedStopFlag&) = delete;
  ScopedStopFlag& operator=(const ScopedStopFlag&) = delete;

 private:
  const std::atomic<bool>* previous_;
};

/// Whether the calling thread was asked to stop.
bool stop_requested();

/// Throws StopRequested when the calling thread was asked to stop. Costs one
/// thread-local load and one relaxed atomic load: call it every iteration of
/// a loop whose iterations take microseconds, every few thousand otherwise.
void check_stop();

/// check_stop() every `every`th call (a counter the loop keeps).
inline void check_stop_every(uint64_t& counter, uint64_t every) {
  if (++counter % every == 0) check_stop();
}

}  // namespace latsim::des
