// A count that only grows, and processes waiting for it to reach a value:
// "frame j has finished stage s" is stage_ended.value() > j.
#pragma once

#include <algorithm>
#include <cstdint>
#include <set>
#include <vector>

#include "latsim/des/process.hpp"

namespace latsim::pipelines::frame_stages {

/// A monotone counter that wakes the processes waiting for it to reach a value.
class Progress {
 public:
  explicit Progress(des::Simulator& sim) : sim_(&sim) {}
  ~Progress() {
    for (Awaiter* w : waiters_) w->registered_ = false;
  }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  int64_t value() const { return value_; }

  /// Raises the value (never lowers it) and resumes, as events at now() in
  /// the order they began to wait, the waiters whose target it reached.
  void raise_to(int64_t v) {
    if (v <= value_) return;
    value_ = v;
    std::vector<Awaiter*> due;
    std::erase_if(waiters_, [&](Awaiter* w) {
      if (w->target_ > value_) return false;
      due.push_back(w);
      return true;
    });
    for (Awaiter* w : due) {
      w->registered_ = false;
      des::ProcessPromise::schedule_resume(w->handle_, sim_->now());
    }
  }
  void advance() { raise_to(value_ + 1); }

  /// Awaiter for `co_await progress.reached(n)`: continues at once if value() >= n.
  class Awaiter {
   public:
    Awaiter(Progress& p, int64_t target) : progress_(&p), target_(target) {}
    Awaiter(const Awaiter&) = delete;  // registered by address
    ~Awaiter() {
      if (registered_) std::erase(progress_->waiters_, this);
    }
    bool await_ready() const noexcept { return progress_->value_ >= target_; }
    void await_suspend(des::ProcessPromise::Handle h) {
      handle_ = h;
      progress_->waiters_.push_back(this);
      registered_ = true;
    }
    void await_resume() const noexcept {}

   private:
    friend class Progress;
    Progress* progress_;
    int64_t target_;
    des::ProcessPromise::Handle handle_;
    bool registered_ = false;
  };
  Awaiter reached(int64_t target) { return Awaiter(*this, target); }

 private:
  des::Simulator* sim_;
  int64_t value_ = 0;
  std::vector<Awaiter*> waiters_;
};

/// Progress over jobs that may finish out of order: value() is the number of
/// jobs 0, 1, ... finished without a gap (job j is done when value() > j).
class PrefixProgress {
 public:
  explicit PrefixProgress(des::Simulator& sim) : progress_(sim) {}
  int64_t value() const { return progress_.value(); }
  /// Marks job j done (again: no effect).
  void mark(int64_t j) {
    if (j < progress_.value()) return;
    pending_.insert(j);
    int64_t v = progress_.value();
    while (!pending_.empty() && *pending_.begin() == v) {
      pending_.erase(pending_.begin());
      ++v;
    }
    progress_.raise_to(v);
  }
  Progress::Awaiter reached(int64_t target) { return progress_.reached(target); }
  /// The count itself, for waits that take any Progress.
  Progress& progress() { return progress_; }

 private:
  Progress progress_;
  std::set<int64_t> pending_;
};

}  // namespace latsim::pipelines::frame_stages
