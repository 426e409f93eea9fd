// Continuing a waiting process inside the event that decides it may go on.
//
//   des::Handoff retrace;
//   co_await retrace;    // in the renderer process: park until a buffer is free
//   retrace.resume();    // in the display's retrace callback: it continues now
//
// A Signal wakes its waiters as new events; a Handoff continues its one
// waiter at once, within the running event, so the continuation belongs to
// that event (the swap at a retrace and the next frame's start are one
// instant of one model) and costs no event of its own.
#pragma once

#include <stdexcept>

#include "latsim/des/process.hpp"

namespace latsim::des {

/// Where at most one process waits to be continued by model code.
class Handoff {
 public:
  Handoff() = default;
  Handoff(const Handoff&) = delete;
  Handoff& operator=(const Handoff&) = delete;

  bool waiting() const { return static_cast<bool>(waiter_); }
  /// Continues the waiting process now, until it next waits or ends; false if none waits.
  bool resume() {
    if (!waiter_) return false;
    const ProcessPromise::Handle h = waiter_;
    waiter_ = nullptr;
    ProcessPromise::resume(h);
    return true;
  }

  /// Awaiter for `co_await handoff`: always parks until resume().
  class Awaiter {
   public:
    explicit Awaiter(Handoff& h) : handoff_(&h) {}
    bool await_ready() const noexcept { return false; }
    void await_suspend(ProcessPromise::Handle h) {
      if (handoff_->waiter_) throw std::logic_error("a Handoff holds one waiting process at a time");
      handoff_->waiter_ = h;
    }
    void await_resume() const noexcept {}

   private:
    Handoff* handoff_;
  };
  Awaiter operator co_await() { return Awaiter(*this); }

 private:
  ProcessPromise::Handle waiter_;
};

}  // namespace latsim::des
