#include "latsim/pipelines/tracker_host.hpp"

#include <algorithm>

namespace latsim::pipelines {

namespace {
// Samples are taken before anything else that happens at the same instant.
constexpr des::Priority kSamplePriority = -10;
constexpr size_t kPruneAbove = 4096;
}  // namespace

TrackerHost::TrackerHost(des::Simulator& sim, tracker::Tracker& tracker, tracker::Transport& transport)
    : sim_(sim), tracker_(tracker), transport_(transport) {
  kind_sample_ = sim_.kind("tracker.sample");
}

void TrackerHost::start(des::Time end) {
  end_ = end;
  tracker::TrackerSample s = tracker_.sample(tracker_.first_index_at_or_after(sim_.now()));
  if (s.measured_at < end_) {
    const des::Time t = std::max(s.measured_at, sim_.now());
    sim_.at(t, kind_sample_, [this, s] { measure(s); }, kSamplePriority);
  }
}

void TrackerHost::on_measured(std::function<void(const tracker::TrackerSample&, des::Time)> fn) {
  measured_fns_.push_back(std::move(fn));
}

void TrackerHost::on_delivery(std::function<void(const tracker::TrackerSample&, des::Time)> fn) {
  if (delivery_fns_.empty()) kind_deliver_ = sim_.kind("transport.deliver");
  delivery_fns_.push_back(std::move(fn));
}

void TrackerHost::measure(tracker::TrackerSample s) {
  ++measured_;
  const des::Time delivered = transport_.deliver(s.ready_at);
  delivered_.push_back(Delivered{delivered, s});
  for (auto& fn : measured_fns_) fn(s, delivered);
  // Delivery events exist only when a pipeline listens for arrivals.
  if (!delivery_fns_.empty())
    sim_.at(delivered, kind_deliver_, [this, s, delivered] {
      for (auto& fn : delivery_fns_) fn(s, delivered);
    });
  if (delivered_.size() > kPruneAbove) prune();
  tracker::TrackerSample next = tracker_.sample(s.index + 1);
  if (next.measured_at < end_) sim_.at(next.measured_at, kind_sample_, [this, next] { measure(next); }, kSamplePriority);
}

void TrackerHost::prune() {
  // Keep one second of history behind the newest sample visible now.
  const des::Time horizon = sim_.now() - des::Time::s(1);
  while (delivered_.size() > 2 && delivered_[1].at <= horizon) delivered_.pop_front();
}

std::optional<tracker::TrackerSample> TrackerHost::newest_at(des::Time t) const {
  // Delivery times never decrease, so the newest visible sample is the last
  // entry delivered at or before t.
  auto it = std::upper_bound(delivered_.begin(), delivered_.end(), t,
                             [](des::Time v, const Delivered& d) { return v < d.at; });
  if (it == delivered_.begin()) return std::nullopt;
  return std::prev(it)->sample;
}

des::Time TrackerHost::received_at(const tracker::TrackerSample& s) const {
  for (auto it = delivered_.rbegin(); it != delivered_.rend(); ++it)
    if (it->sample.index == s.index) return it->at;
  return s.ready_at;
}

}  // namespace latsim::pipelines
