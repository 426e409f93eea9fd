#include "latsim/des/periodic.hpp"

namespace latsim::des {

Periodic::Periodic(Simulator& sim, PeriodicSchedule schedule, KindId kind, std::function<void(int64_t)> fn,
                   Priority prio)
    : sim_(sim), schedule_(schedule), kind_(kind), fn_(std::move(fn)), prio_(prio) {}

void Periodic::start(int64_t first, Time end) {
  stop();
  end_ = end;
  schedule_next(first);
}

void Periodic::stop() {
  if (pending_.valid()) sim_.cancel(pending_);
  pending_ = EventId{};
}

void Periodic::schedule_next(int64_t k) {
  const Time at = schedule_.at(k);
  if (at >= end_) {
    pending_ = EventId{};
    return;
  }
  pending_ = sim_.at(at, kind_, [this, k] {
    schedule_next(k + 1);
    ++count_;
    fn_(k);
  }, prio_);
}

}  // namespace latsim::des
