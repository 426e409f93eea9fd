#include "latsim/run/device_feed.hpp"

#include <algorithm>
#include <stdexcept>

namespace latsim::run {

namespace {
// Reports are taken before anything else at the same instant, as the head's samples are.
constexpr des::Priority kSamplePriority = -10;
// Keep about a second of reports behind the newest visible one.
constexpr size_t kPruneAbove = 4096;
}  // namespace

DeviceFeed::DeviceFeed(des::Simulator& sim, std::unique_ptr<tracker::Tracker> tracker,
                       std::unique_ptr<tracker::Transport> transport, std::unique_ptr<tracker::RuntimeFusion> fusion,
                       const tracker::PredictionParams& prediction, const std::string& name)
    : sim_(sim),
      tracker_(std::move(tracker)),
      transport_(std::move(transport)),
      fusion_(std::move(fusion)),
      prediction_(prediction) {
  if (transport_->occupancy() > des::Time::zero())
    throw std::invalid_argument("a device's own link must not keep records waiting (no serial line)");
  kind_ = sim_.kind(name + ".sample");
}

void DeviceFeed::start(des::Time end) {
  end_ = end;
  const tracker::TrackerSample s = tracker_->sample(tracker_->first_index_at_or_after(sim_.now()));
  if (s.measured_at < end_) sim_.at(std::max(s.measured_at, sim_.now()), kind_, [this, s] { measure(s); }, kSamplePriority);
}

des::Time DeviceFeed::stamp_of(const tracker::TrackerSample& s, const tracker::Carriage& c) const {
  if (prediction_.params().knowledge == tracker::PredictionKnowledge::oracle) return s.measured_at;
  return c.visible - transport_->occupancy() - tracker_->params().internal_delay;
}

void DeviceFeed::measure(const tracker::TrackerSample& s) {
  ++reports_;
  if (s.lost) {
    ++lost_;
  } else {
    const tracker::Carriage c = transport_->carry(s.ready_at);
    const tracker::TrackerSample seen = fusion_ ? fusion_->fuse(s, c.visible) : s;
    prediction_.observe(seen, stamp_of(s, c));
    delivered_.push_back(Delivered{c.visible, seen});
    if (delivered_.size() > kPruneAbove) {
      const des::Time horizon = sim_.now() - des::Time::s(1);
      while (delivered_.size() > 2 && delivered_[1].at <= horizon) delivered_.pop_front();
      prediction_.forget_before(delivered_.front().sample.index);
    }
  }
  const tracker::TrackerSample next = tracker_->sample(tracker_->next_index(s.index));
  if (next.measured_at < end_) sim_.at(next.measured_at, kind_, [this, next] { measure(next); }, kSamplePriority);
}

std::optional<tracker::TrackerSample> DeviceFeed::newest_at(des::Time t) const {
  const auto it = std::upper_bound(delivered_.begin(), delivered_.end(), t,
                                   [](des::Time v, const Delivered& d) { return v < d.at; });
  if (it == delivered_.begin()) return std::nullopt;
  return std::prev(it)->sample;
}

}  // namespace latsim::run
