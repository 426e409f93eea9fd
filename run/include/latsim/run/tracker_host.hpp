// Runs the tracker as events, carries its records to the host and keeps what
// the host application can see.
#pragma once

#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "latsim/des/simulator.hpp"
#include "latsim/results/image_record.hpp"
#include "latsim/run/device_feed.hpp"
#include "latsim/tracker/host_feed.hpp"
#include "latsim/tracker/imu_chain.hpp"
#include "latsim/tracker/host_prediction.hpp"
#include "latsim/tracker/tracker.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::results {
class Timeline;
}

namespace latsim::run {

/// One event per tracker sample at its measurement time. Each record goes to
/// the link when it is ready; one that finds the link busy waits in the
/// link's buffer (drop-oldest when full), and a line event starts the next
/// waiting record when the link frees (no events when nothing waits).
/// newest_at(t) answers with the newest sample visible at t (several
/// arriving at one poll: the newest wins). With prediction, every record
/// also goes through the host's predictor as it is put on the link (no extra
/// events; a record pushed out of the buffer never reaches the host, so the
/// predictor never sees it; an estimate is used only once its sample is
/// visible, so nothing is known early).
class TrackerHost final : public tracker::HostFeed {
 public:
  TrackerHost(des::Simulator& sim, tracker::Tracker& tracker, tracker::Transport& transport,
              results::Timeline* timeline = nullptr,
              const std::optional<tracker::PredictionParams>& prediction = std::nullopt);

  /// Tracks a handheld controller too: every record carries its pose,
  /// measured at the head sample's instant (noise from `noise`), and the
  /// host predicts it with a predictor of its own of the head's settings.
  void track_controller(const tracker::MotionSource& motion, des::RandomStream noise);
  std::optional<tracker::PosePrediction> controller_for(const tracker::PosePrediction& head) const override;
  /// Tracks the controller with a chain of its own (its IMU, link and
  /// fusion): each image draws the newest controller report the host had
  /// when the image's head pose was read, predicted to the same instant.
  void track_controller(std::unique_ptr<DeviceFeed> feed) { controller_feed_ = std::move(feed); }
  /// The runtime's fusion of the head's IMU chain, applied to each report as
  /// it becomes visible to the host (none: measured poses are used as they are).
  void fuse_with(std::unique_ptr<tracker::RuntimeFusion> fusion) { fusion_ = std::move(fusion); }
  const DeviceFeed* controller_feed() const { return controller_feed_.get(); }

  /// Schedules samples measured in [now, end).
  void start(des::Time end);
  /// Called with (sample, carriage) as each record is given to the link (in link order).
  void on_carried(std::function<void(const tracker::TrackerSample&, const tracker::Carriage&)> fn);

  std::optional<tracker::TrackerSample> newest_at(des::Time t) const override;
  des::Time received_at(const tracker::TrackerSample& s) const override;
  void on_delivery(std::function<void(const tracker::TrackerSample&, des::Time)> fn) override;
  tracker::PredictionBasis basis_of(const tracker::TrackerSample& s) const override { return prediction_.basis_of(s); }
  bool predicts() const override { return predicts_; }
  int64_t samples_measured() const { return measured_; }
  /// Records pushed out of a full link buffer before they could be sent.
  int64_t records_dropped() const { return dropped_; }
  /// Records waiting for the link at the end (never sent within the run).
  int64_t records_waiting() const { return static_cast<int64_t>(waiting_.size()); }

 private:
  void measure(tracker::TrackerSample s);
  void offer(const tracker::TrackerSample& s);
  void advance(des::Time t);
  void send(const tracker::TrackerSample& raw, des::Time start);
  void line_free();
  void prune();
  // When the host believes a record carried as `c` was measured: its
  // measurement time for an oracle host; for a runtime host, when the record
  // became visible on the host's clock less the delays it knows of (the
  // tracker's internal delay and the record's time on the link), so that
  // waits for a poll, queueing on the line and interrupt handlers are unknown
  // to it (tracker jitter is not: a sample measured late arrives late).
  des::Time stamp_of(const tracker::TrackerSample& s, const tracker::Carriage& c) const;

  struct Delivered {
    des::Time at;
    tracker::TrackerSample sample;
  };
  des::Simulator& sim_;
  tracker::Tracker& tracker_;
  tracker::Transport& transport_;
  results::Timeline* timeline_;
  tracker::HostPrediction prediction_;
  bool predicts_ = false;
  des::Time end_;
  std::deque<Delivered> delivered_;
  std::deque<tracker::TrackerSample> waiting_;  // ready, not yet on the link, oldest first
  des::Time link_free_at_;
  bool line_event_pending_ = false;
  std::vector<std::function<void(const tracker::TrackerSample&, des::Time)>> delivery_fns_;
  std::vector<std::function<void(const tracker::TrackerSample&, const tracker::Carriage&)>> carried_fns_;
  des::KindId kind_sample_ = 0, kind_deliver_ = 0, kind_line_ = 0;
  int64_t measured_ = 0;
  int64_t dropped_ = 0;
  // The controller: its samples sent (increasing index, pruned with the
  // head's) and the host's predictions of it.
  struct Controller {
    const tracker::MotionSource* motion;
    des::RandomStream noise;
    tracker::HostPrediction prediction;
    std::deque<tracker::TrackerSample> sent;
  };
  std::optional<Controller> controller_;
  std::unique_ptr<DeviceFeed> controller_feed_;
  std::unique_ptr<tracker::RuntimeFusion> fusion_;
};

}  // namespace latsim::run
