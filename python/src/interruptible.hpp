// Long C++ work called from Python that Ctrl-C can stop.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>

namespace latsim::python {

/// How often the calling thread looks for a signal while the work runs.
inline constexpr std::chrono::milliseconds kSignalPoll{50};

/// Runs `work` on a thread of its own while the calling thread, the GIL
/// released, asks Python every kSignalPoll whether a signal came (Ctrl-C,
/// a notebook's interrupt). When a signal handler raises, `stop` is set, the
/// work ends at its next event, and the handler's exception
/// (KeyboardInterrupt) is raised once it has; otherwise what `work` threw is
/// rethrown here. Call with the GIL held.
void run_interruptibly(const std::function<void(const std::atomic<bool>& stop)>& work);

}  // namespace latsim::python
