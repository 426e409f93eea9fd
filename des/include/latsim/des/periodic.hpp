// A periodic activity: fn(k) at every time of an exact periodic schedule.
//
//   des::Periodic ticks(sim, des::PeriodicSchedule(Time::zero(), {1, 60}), sim.kind("app.tick"),
//                       [&](int64_t k) { ... });
//   ticks.start(0, end);   // occurrences 0, 1, 2 ... before `end`
//
// Occurrence k is an event of `kind` at schedule.at(k), computed from the
// index (exact over hours, at 59.94 Hz too). Each occurrence schedules the
// next one before fn(k) runs, so whatever fn schedules for the same instant
// comes after the next tick in the tie order.
#pragma once

#include <cstdint>
#include <functional>

#include "latsim/des/simulator.hpp"

namespace latsim::des {

/// Calls a function at every occurrence of a schedule, as events of one kind.
class Periodic {
 public:
  Periodic(Simulator& sim, PeriodicSchedule schedule, KindId kind, std::function<void(int64_t)> fn, Priority prio = 0);
  Periodic(const Periodic&) = delete;  // pending events refer to this object
  Periodic& operator=(const Periodic&) = delete;

  /// Schedules occurrences first, first + 1, ... whose time is before `end`.
  void start(int64_t first, Time end);
  /// Cancels the pending occurrence; start() may be called again.
  void stop();
  const PeriodicSchedule& schedule() const { return schedule_; }
  /// Occurrences run so far.
  int64_t count() const { return count_; }

 private:
  void schedule_next(int64_t k);

  Simulator& sim_;
  PeriodicSchedule schedule_;
  KindId kind_;
  std::function<void(int64_t)> fn_;
  Priority prio_;
  Time end_;
  EventId pending_;
  int64_t count_ = 0;
};

}  // namespace latsim::des
