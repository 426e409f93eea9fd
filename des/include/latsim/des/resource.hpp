// Resources: a pool of identical units that processes acquire and release,
// queueing first-come first-served when all are in use.
//
//   Resource ring(sim, 1, "ring");
//   co_await ring.acquire();
//   co_await sim.delay(copy_time);
//   ring.release();
//
// release() hands a freed unit straight to the longest waiter, so a process
// arriving later can never overtake one already queued.
#pragma once

#include <deque>
#include <string>

#include "latsim/des/process.hpp"

namespace latsim::des {

/// A counted resource with a FIFO queue of waiting processes and busy-time accounting.
class Resource {
 public:
  explicit Resource(Simulator& sim, int capacity = 1, std::string name = {});
  ~Resource();
  Resource(const Resource&) = delete;
  Resource& operator=(const Resource&) = delete;

  /// Awaiter for `co_await res.acquire()`: continues at once when a unit is
  /// free and nobody is queued, otherwise joins the back of the queue.
  class AcquireAwaiter {
   public:
    explicit AcquireAwaiter(Resource& r) : resource_(&r) {}
    AcquireAwaiter(const AcquireAwaiter&) = delete;  // queued by address
    ~AcquireAwaiter();
    bool await_ready();
    void await_suspend(ProcessPromise::Handle h);
    void await_resume() const noexcept {}

   private:
    friend class Resource;
    Resource* resource_;
    ProcessPromise::Handle handle_;
    bool queued_ = false;
  };

  AcquireAwaiter acquire() { return AcquireAwaiter(*this); }
  /// Takes a unit without waiting; false if none is free or others are queued.
  bool try_acquire();
  /// Returns a unit; the longest waiter (if any) gets it and resumes at now().
  /// Throws std::logic_error if no unit is in use.
  void release();

  int capacity() const { return capacity_; }
  int in_use() const { return in_use_; }
  std::size_t queue_length() const { return queue_.size(); }
  const std::string& name() const { return name_; }

  /// Time during which at least one unit was in use, up to now(). For
  /// capacity 1 this is the busy time; utilisation = busy_time / elapsed.
  Time busy_time() const;
  /// Integral of units in use over time, up to now() (unit-seconds): for any
  /// capacity, mean utilisation = unit_busy_time / (capacity * elapsed).
  Time unit_busy_time() const;

 private:
  void set_in_use(int n);

  Simulator* sim_;
  int capacity_;
  std::string name_;
  int in_use_ = 0;
  std::deque<AcquireAwaiter*> queue_;
  Time last_change_;
  Time busy_;       // accumulated up to last_change_
  Time unit_busy_;  // accumulated up to last_change_
};

}  // namespace latsim::des
