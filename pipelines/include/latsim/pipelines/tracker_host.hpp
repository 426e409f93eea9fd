// Runs the tracker as events and keeps what the host application can see.
#pragma once

#include <deque>
#include <functional>
#include <vector>

#include "latsim/des/simulator.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/tracker/tracker.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::pipelines {

/// One event per tracker sample at its measurement time; the transport gives
/// the instant the host can see it; newest_at(t) answers with the newest
/// sample visible at t (several arriving at one poll: the newest wins).
class TrackerHost final : public HostFeed {
 public:
  TrackerHost(des::Simulator& sim, tracker::Tracker& tracker, tracker::Transport& transport);

  /// Schedules samples measured in [now, end).
  void start(des::Time end);
  /// Called with (sample, delivery time) as each sample is measured (for statistics).
  void on_measured(std::function<void(const tracker::TrackerSample&, des::Time delivered)> fn);

  std::optional<tracker::TrackerSample> newest_at(des::Time t) const override;
  des::Time received_at(const tracker::TrackerSample& s) const override;
  void on_delivery(std::function<void(const tracker::TrackerSample&, des::Time)> fn) override;
  int64_t samples_measured() const { return measured_; }

 private:
  void measure(tracker::TrackerSample s);
  void prune();

  struct Delivered {
    des::Time at;
    tracker::TrackerSample sample;
  };
  des::Simulator& sim_;
  tracker::Tracker& tracker_;
  tracker::Transport& transport_;
  des::Time end_;
  std::deque<Delivered> delivered_;
  std::vector<std::function<void(const tracker::TrackerSample&, des::Time)>> delivery_fns_;
  std::vector<std::function<void(const tracker::TrackerSample&, des::Time)>> measured_fns_;
  des::KindId kind_sample_ = 0, kind_deliver_ = 0;
  int64_t measured_ = 0;
};

}  // namespace latsim::pipelines
