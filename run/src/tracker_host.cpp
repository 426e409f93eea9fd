#include "latsim/run/tracker_host.hpp"

#include <algorithm>

#include "latsim/results/timeline.hpp"

namespace latsim::run {

namespace {
// Samples are taken before anything else that happens at the same instant.
constexpr des::Priority kSamplePriority = -10;
constexpr size_t kPruneAbove = 4096;
}  // namespace

TrackerHost::TrackerHost(des::Simulator& sim, tracker::Tracker& tracker, tracker::Transport& transport,
                         results::Timeline* timeline, const std::optional<tracker::PredictionParams>& prediction)
    : sim_(sim),
      tracker_(tracker),
      transport_(transport),
      timeline_(timeline),
      prediction_(prediction.value_or(tracker::PredictionParams{})),
      predicts_(prediction.has_value()) {
  kind_sample_ = sim_.kind("tracker.sample");
}

void TrackerHost::start(des::Time end) {
  end_ = end;
  if (controller_feed_) controller_feed_->start(end);
  tracker::TrackerSample s = tracker_.sample(tracker_.first_index_at_or_after(sim_.now()));
  if (s.measured_at < end_) {
    const des::Time t = std::max(s.measured_at, sim_.now());
    sim_.at(t, kind_sample_, [this, s] { measure(s); }, kSamplePriority);
  }
}

void TrackerHost::track_controller(const tracker::MotionSource& motion, des::RandomStream noise) {
  controller_.emplace(Controller{&motion, std::move(noise), tracker::HostPrediction(prediction_.params()), {}});
}

std::optional<tracker::PosePrediction> TrackerHost::controller_for(const tracker::PosePrediction& head) const {
  if (controller_feed_) {
    // Its own chain: the newest controller report the host had when the
    // head's pose was read, predicted to the same instant.
    const std::optional<tracker::TrackerSample> c =
        controller_feed_->newest_at(head.read_at ? *head.read_at : received_at(head.sample));
    if (!c) return std::nullopt;
    tracker::PredictionBasis basis = controller_feed_->basis_of(*c);
    basis.fixed_horizon.reset();
    return basis.for_photon_time(head.target);
  }
  if (!controller_) return std::nullopt;
  const auto& sent = controller_->sent;
  const auto it = std::lower_bound(sent.begin(), sent.end(), head.sample.index,
                                   [](const tracker::TrackerSample& c, int64_t i) { return c.index < i; });
  tracker::PredictionBasis basis;
  if (it == sent.end() || it->index != head.sample.index) {
    // Held longer than the host remembers (about a second): drawn where the
    // controller was at the sample's instant, unpredicted.
    tracker::TrackerSample old = head.sample;
    old.pose = controller_->motion->pose_at(old.measured_at);
    basis = tracker::hold_basis(old);
  } else {
    basis = controller_->prediction.basis_of(*it);
  }
  // The head's pose may be for a fixed horizon or a photon time; the
  // controller's is for the same instant.
  basis.fixed_horizon.reset();
  return basis.for_photon_time(head.target);
}

void TrackerHost::on_carried(std::function<void(const tracker::TrackerSample&, const tracker::Carriage&)> fn) {
  carried_fns_.push_back(std::move(fn));
}

void TrackerHost::on_delivery(std::function<void(const tracker::TrackerSample&, des::Time)> fn) {
  if (delivery_fns_.empty()) kind_deliver_ = sim_.kind("transport.deliver");
  delivery_fns_.push_back(std::move(fn));
}

void TrackerHost::measure(tracker::TrackerSample s) {
  ++measured_;
  if (timeline_ && s.ready_at > s.measured_at) timeline_->add("TRACKER", s.index, -1, "tracker", s.measured_at, s.ready_at);
  // A lost report (an IMU chain's) never reaches the link.
  if (!s.lost) offer(s);
  if (delivered_.size() > kPruneAbove) prune();
  tracker::TrackerSample next = tracker_.sample(tracker_.next_index(s.index));
  if (next.measured_at < end_) sim_.at(next.measured_at, kind_sample_, [this, next] { measure(next); }, kSamplePriority);
}

// Everything that decides a record's fate up to its ready time is known when
// it is measured (records are ready in index order), so the link is brought
// up to that instant and the record is sent, or waits, or pushes out the
// oldest waiting record.
void TrackerHost::offer(const tracker::TrackerSample& s) {
  advance(s.ready_at);
  if (waiting_.empty() && link_free_at_ <= s.ready_at) {
    send(s, s.ready_at);
    return;
  }
  waiting_.push_back(s);
  if (static_cast<int64_t>(waiting_.size()) > transport_.buffer_records()) {
    const tracker::TrackerSample& old = waiting_.front();
    if (timeline_) timeline_->add("DROPPED", old.index, -1, "serial buffer", old.ready_at, s.ready_at);
    waiting_.pop_front();
    ++dropped_;
  }
  if (!line_event_pending_) {
    if (kind_line_ == 0) kind_line_ = sim_.kind("transport.line");
    line_event_pending_ = true;
    sim_.at(link_free_at_, kind_line_, [this] { line_free(); });
  }
}

// Starts every waiting record whose turn on the link comes at or before t.
void TrackerHost::advance(des::Time t) {
  while (!waiting_.empty() && link_free_at_ <= t) {
    const tracker::TrackerSample next = waiting_.front();
    waiting_.pop_front();
    send(next, std::max(link_free_at_, next.ready_at));
  }
}

void TrackerHost::line_free() {
  line_event_pending_ = false;
  advance(sim_.now());
  if (waiting_.empty()) return;
  line_event_pending_ = true;
  sim_.at(link_free_at_, kind_line_, [this] { line_free(); });
}

void TrackerHost::send(const tracker::TrackerSample& raw, des::Time start) {
  const tracker::Carriage c = transport_.carry(start);
  // An IMU chain's report is fused by the runtime as it becomes visible:
  // from here on the host knows the fused pose, never the measured one.
  const tracker::TrackerSample s = fusion_ ? fusion_->fuse(raw, c.visible) : raw;
  link_free_at_ = start + transport_.occupancy();
  prediction_.observe(s, stamp_of(s, c));
  if (controller_) {
    tracker::TrackerSample cs = s;
    cs.pose = tracker_.measure_object(*controller_->motion, s.measured_at, controller_->noise);
    controller_->prediction.observe(cs, stamp_of(s, c));
    controller_->sent.push_back(cs);
  }
  delivered_.push_back(Delivered{c.visible, s});
  for (auto& fn : carried_fns_) fn(s, c);
  if (timeline_ && transport_.occupancy() > des::Time::zero()) {
    if (c.start > s.ready_at) timeline_->add("QUEUED", s.index, -1, "serial buffer", s.ready_at, c.start);
    timeline_->add("SEND", s.index, -1, "serial line", c.start, c.end);
    if (c.visible > c.end) timeline_->add("HOST WAIT", s.index, -1, "host kernel", c.end, c.visible);
  }
  // Delivery events exist only when a pipeline listens for arrivals.
  if (!delivery_fns_.empty()) {
    const des::Time at = c.visible;
    sim_.at(at, kind_deliver_, [this, s, at] {
      for (auto& fn : delivery_fns_) fn(s, at);
    });
  }
}

des::Time TrackerHost::stamp_of(const tracker::TrackerSample& s, const tracker::Carriage& c) const {
  if (prediction_.params().knowledge == tracker::PredictionKnowledge::oracle) return s.measured_at;
  return c.visible - transport_.occupancy() - tracker_.params().internal_delay;
}

void TrackerHost::prune() {
  // Keep one second of history behind the newest sample visible now.
  const des::Time horizon = sim_.now() - des::Time::s(1);
  while (delivered_.size() > 2 && delivered_[1].at <= horizon) delivered_.pop_front();
  prediction_.forget_before(delivered_.front().sample.index);
  if (controller_) {
    const int64_t keep = delivered_.front().sample.index;
    while (!controller_->sent.empty() && controller_->sent.front().index < keep) controller_->sent.pop_front();
    controller_->prediction.forget_before(keep);
  }
}

std::optional<tracker::TrackerSample> TrackerHost::newest_at(des::Time t) const {
  // Delivery times never decrease, so the newest visible sample is the last
  // entry delivered at or before t. Pipelines ask about now or just before:
  // a few steps back from the newest entry, then a binary search.
  auto it = delivered_.end();
  for (int k = 0; k < 4 && it != delivered_.begin(); ++k, --it)
    if (std::prev(it)->at <= t) return std::prev(it)->sample;
  it = std::upper_bound(delivered_.begin(), it, t, [](des::Time v, const Delivered& d) { return v < d.at; });
  if (it == delivered_.begin()) return std::nullopt;
  return std::prev(it)->sample;
}

des::Time TrackerHost::received_at(const tracker::TrackerSample& s) const {
  for (auto it = delivered_.rbegin(); it != delivered_.rend(); ++it)
    if (it->sample.index == s.index) return it->at;
  return s.ready_at;
}

}  // namespace latsim::run
