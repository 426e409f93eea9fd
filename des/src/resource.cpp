#include "latsim/des/resource.hpp"

#include <algorithm>
#include <stdexcept>

namespace latsim::des {

Resource::Resource(Simulator& sim, int capacity, std::string name)
    : sim_(&sim), capacity_(capacity), name_(std::move(name)), last_change_(sim.now()) {
  if (capacity < 1)
    throw std::invalid_argument("resource '" + name_ + "' needs a capacity of at least 1, got " +
                                std::to_string(capacity));
}

Resource::~Resource() {
  for (AcquireAwaiter* w : queue_) w->queued_ = false;
}

bool Resource::try_acquire() {
  if (in_use_ >= capacity_ || !queue_.empty()) return false;
  set_in_use(in_use_ + 1);
  return true;
}

void Resource::release() {
  if (in_use_ <= 0)
    throw std::logic_error("release() of resource '" + name_ + "' with no unit in use; acquire before releasing");
  if (queue_.empty()) {
    set_in_use(in_use_ - 1);
    return;
  }
  // Hand the unit over: in_use stays the same and the waiter resumes now.
  AcquireAwaiter* next = queue_.front();
  queue_.pop_front();
  next->queued_ = false;
  ProcessPromise::schedule_resume(next->handle_, sim_->now());
}

void Resource::set_in_use(int n) {
  const Time now = sim_->now();
  const Time span = now - last_change_;
  if (in_use_ > 0) busy_ += span;
  unit_busy_ += span * in_use_;
  last_change_ = now;
  in_use_ = n;
}

Time Resource::busy_time() const {
  return in_use_ > 0 ? busy_ + (sim_->now() - last_change_) : busy_;
}

Time Resource::unit_busy_time() const { return unit_busy_ + (sim_->now() - last_change_) * in_use_; }

Resource::AcquireAwaiter::~AcquireAwaiter() {
  if (queued_) std::erase(resource_->queue_, this);
}

bool Resource::AcquireAwaiter::await_ready() { return resource_->try_acquire(); }

void Resource::AcquireAwaiter::await_suspend(ProcessPromise::Handle h) {
  handle_ = h;
  resource_->queue_.push_back(this);
  queued_ = true;
}

}  // namespace latsim::des
