// Signals: one-shot conditions that processes wait on.
//
//   Signal frame_done(sim, "frame_done");
//   co_await frame_done;                      // in one process
//   frame_done.trigger();                     // in another
//   co_await all_of(left_done, right_done);   // both eyes
//
// Waiters resume as events at the trigger time, in the order they started
// waiting. Triggering an already triggered signal is an error (call reset()
// first): a silent second trigger usually hides a modelling mistake.
#pragma once

#include <string>
#include <vector>

#include "latsim/des/process.hpp"

namespace latsim::des {

class Signal;

/// Something registered with one or more signals, told when each triggers.
class SignalWaiter {
 public:
  virtual void on_trigger(Signal& s) = 0;
  /// The signal is going away while this still waits on it (simulator teardown).
  virtual void on_signal_destroyed(Signal& s) = 0;

 protected:
  SignalWaiter() = default;
  SignalWaiter(const SignalWaiter&) = default;
  ~SignalWaiter() = default;
};

/// A condition that becomes true once (until reset) and wakes its waiters.
class Signal {
 public:
  explicit Signal(Simulator& sim, std::string name = {}) : sim_(&sim), name_(std::move(name)) {}
  ~Signal();
  Signal(const Signal&) = delete;
  Signal& operator=(const Signal&) = delete;

  /// Marks the signal triggered and schedules every waiter at now(), FIFO.
  /// Throws std::logic_error if it is already triggered.
  void trigger();
  bool triggered() const { return triggered_; }
  /// Makes the signal untriggered again; later co_awaits wait for a new trigger.
  void reset() { triggered_ = false; }
  const std::string& name() const { return name_; }
  Simulator& simulator() const { return *sim_; }
  std::size_t waiter_count() const { return waiters_.size(); }

  void add_waiter(SignalWaiter* w) { waiters_.push_back(w); }
  void remove_waiter(SignalWaiter* w);

  /// Awaiter for `co_await signal`: continues at once if already triggered.
  class Awaiter final : public SignalWaiter {
   public:
    explicit Awaiter(Signal& s) : signal_(&s) {}
    Awaiter(const Awaiter&) = delete;  // registered by address
    ~Awaiter();
    bool await_ready() const noexcept { return signal_->triggered(); }
    void await_suspend(ProcessPromise::Handle h);
    void await_resume() const noexcept {}
    void on_trigger(Signal& s) override;
    void on_signal_destroyed(Signal&) override { registered_ = false; }

   private:
    friend class Signal;
    Signal* signal_;
    ProcessPromise::Handle handle_;
    bool registered_ = false;
  };

  Awaiter operator co_await() { return Awaiter(*this); }

 private:
  Simulator* sim_;
  std::string name_;
  bool triggered_ = false;
  std::vector<SignalWaiter*> waiters_;
};

/// Awaiter for all_of / any_of over several signals.
class SignalSetAwaiter final : public SignalWaiter {
 public:
  /// Whether every signal or the first one ends the wait.
  enum class Mode { all, any };
  SignalSetAwaiter(Mode mode, std::vector<Signal*> signals) : mode_(mode), signals_(std::move(signals)) {}
  SignalSetAwaiter(const SignalSetAwaiter&) = delete;  // registered by address
  ~SignalSetAwaiter();

  bool await_ready() const;
  void await_suspend(ProcessPromise::Handle h);
  void await_resume() const noexcept {}
  void on_trigger(Signal& s) override;
  void on_signal_destroyed(Signal& s) override;

 private:
  void unregister_all();
  void wake();

  Mode mode_;
  std::vector<Signal*> signals_;
  ProcessPromise::Handle handle_;
  std::size_t remaining_ = 0;
  bool registered_ = false;
};

/// Waits until every signal has triggered (continues at once if all have).
SignalSetAwaiter all_of(std::vector<Signal*> signals);
/// Waits until at least one signal has triggered (continues at once if one has).
SignalSetAwaiter any_of(std::vector<Signal*> signals);

template <class... S>
SignalSetAwaiter all_of(Signal& first, S&... rest) {
  return all_of(std::vector<Signal*>{&first, &rest...});
}
template <class... S>
SignalSetAwaiter any_of(Signal& first, S&... rest) {
  return any_of(std::vector<Signal*>{&first, &rest...});
}

}  // namespace latsim::des
