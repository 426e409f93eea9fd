// Coroutine processes: a model written as straight-line code that waits on
// simulated time, signals and resources.
//
//   Process blink(Simulator& sim, int times) {
//     for (int i = 0; i < times; ++i) co_await sim.delay(Time::ms(500));
//   }
//   sim.spawn(blink(sim, 3));
//
// Every start and resumption is an ordinary event of the process's kind, so
// processes and plain callbacks share one ordering. An exception escaping a
// process propagates out of Simulator::run().
#pragma once

#include <coroutine>
#include <exception>

#include "latsim/des/simulator.hpp"

namespace latsim::des {

/// Coroutine state shared by every Process: its simulator, event kind and a
/// failure to report; also links the frame into the simulator's list of
/// unfinished processes so the simulator can destroy them at the end.
class ProcessPromise {
 public:
  using Handle = std::coroutine_handle<ProcessPromise>;

  Process get_return_object();
  std::suspend_always initial_suspend() noexcept { return {}; }
  // Suspending at the end lets resume() see done() and report exceptions.
  std::suspend_always final_suspend() noexcept { return {}; }
  void return_void() noexcept {}
  void unhandled_exception() noexcept { error_ = std::current_exception(); }

  Simulator& simulator() const { return *sim_; }
  KindId kind() const { return kind_; }

  /// Schedules the resumption of h at absolute time t (an event of its kind).
  static void schedule_resume(Handle h, Time t);
  /// Resumes h; destroys the frame when it finishes and rethrows its error.
  static void resume(Handle h);

 private:
  friend class Simulator;

  void attach(Simulator& sim, KindId kind);
  void detach();

  Simulator* sim_ = nullptr;
  KindId kind_ = 0;
  std::exception_ptr error_;
  ProcessPromise* prev_ = nullptr;
  ProcessPromise* next_ = nullptr;
};

/// The return type of a simulation coroutine; owns the frame until spawned.
class Process {
 public:
  using promise_type = ProcessPromise;

  Process(Process&& o) noexcept : handle_(o.handle_) { o.handle_ = nullptr; }
  Process& operator=(Process&& o) noexcept {
    if (this != &o) {
      if (handle_) handle_.destroy();
      handle_ = o.handle_;
      o.handle_ = nullptr;
    }
    return *this;
  }
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;
  ~Process() {
    if (handle_) handle_.destroy();
  }

 private:
  friend class ProcessPromise;
  friend class Simulator;
  explicit Process(ProcessPromise::Handle h) : handle_(h) {}
  ProcessPromise::Handle release() {
    auto h = handle_;
    handle_ = nullptr;
    return h;
  }

  ProcessPromise::Handle handle_;
};

inline Process ProcessPromise::get_return_object() { return Process(Handle::from_promise(*this)); }

/// Awaitable that resumes the awaiting process at a given absolute time.
class DelayAwaitable {
 public:
  explicit DelayAwaitable(Time wake) : wake_(wake) {}
  bool await_ready() const noexcept { return false; }
  void await_suspend(ProcessPromise::Handle h) const { ProcessPromise::schedule_resume(h, wake_); }
  void await_resume() const noexcept {}

 private:
  Time wake_;
};

}  // namespace latsim::des
