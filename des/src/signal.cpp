#include "latsim/des/signal.hpp"

#include <algorithm>
#include <stdexcept>

namespace latsim::des {

Signal::~Signal() {
  // Waiters outliving the signal (frames destroyed later) must not call back.
  std::vector<SignalWaiter*> waiters;
  waiters.swap(waiters_);
  for (SignalWaiter* w : waiters) w->on_signal_destroyed(*this);
}

void Signal::trigger() {
  if (triggered_)
    throw std::logic_error("signal '" + name_ + "' triggered twice at " + sim_->now().str() +
                           "; call reset() before triggering it again");
  triggered_ = true;
  // Take the list first: a waiter may unregister itself from other signals.
  std::vector<SignalWaiter*> waiters;
  waiters.swap(waiters_);
  for (SignalWaiter* w : waiters) w->on_trigger(*this);
}

void Signal::remove_waiter(SignalWaiter* w) { std::erase(waiters_, w); }

Signal::Awaiter::~Awaiter() {
  if (registered_) signal_->remove_waiter(this);
}

void Signal::Awaiter::await_suspend(ProcessPromise::Handle h) {
  handle_ = h;
  signal_->add_waiter(this);
  registered_ = true;
}

void Signal::Awaiter::on_trigger(Signal&) {
  registered_ = false;
  ProcessPromise::schedule_resume(handle_, signal_->simulator().now());
}

SignalSetAwaiter::~SignalSetAwaiter() { unregister_all(); }

bool SignalSetAwaiter::await_ready() const {
  if (mode_ == Mode::all) {
    return std::all_of(signals_.begin(), signals_.end(), [](const Signal* s) { return s->triggered(); });
  }
  return signals_.empty() ||
         std::any_of(signals_.begin(), signals_.end(), [](const Signal* s) { return s->triggered(); });
}

void SignalSetAwaiter::await_suspend(ProcessPromise::Handle h) {
  handle_ = h;
  remaining_ = 0;
  for (Signal* s : signals_) {
    if (!s->triggered()) {
      s->add_waiter(this);
      ++remaining_;
    }
  }
  registered_ = true;
}

void SignalSetAwaiter::on_trigger(Signal& s) {
  // The triggering signal has already dropped this waiter from its list;
  // forget it too, so that it may be destroyed before this awaiter.
  std::erase(signals_, &s);
  if (mode_ == Mode::all && --remaining_ > 0) return;
  wake();
}

void SignalSetAwaiter::on_signal_destroyed(Signal& s) { std::erase(signals_, &s); }

void SignalSetAwaiter::wake() {
  unregister_all();
  ProcessPromise::schedule_resume(handle_, handle_.promise().simulator().now());
}

void SignalSetAwaiter::unregister_all() {
  if (!registered_) return;
  registered_ = false;
  for (Signal* s : signals_) s->remove_waiter(this);
}

SignalSetAwaiter all_of(std::vector<Signal*> signals) {
  return SignalSetAwaiter(SignalSetAwaiter::Mode::all, std::move(signals));
}

SignalSetAwaiter any_of(std::vector<Signal*> signals) {
  return SignalSetAwaiter(SignalSetAwaiter::Mode::any, std::move(signals));
}

}  // namespace latsim::des
