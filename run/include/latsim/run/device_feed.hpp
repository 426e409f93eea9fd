// A tracked device with a chain of its own (a handheld controller): its
// reports as events, carried by its own link, fused and predicted by the
// runtime, kept for the pipeline to draw it from.
#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "latsim/des/simulator.hpp"
#include "latsim/tracker/host_prediction.hpp"
#include "latsim/tracker/imu_chain.hpp"
#include "latsim/tracker/tracker.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::run {

/// One event per report at its measurement time; the report crosses the
/// device's link at once (links that keep records waiting, a serial line,
/// are not for such devices), is fused when the host can see it and goes
/// through the runtime's predictor. newest_at(t) is the newest report
/// visible at t. Lost reports cost their event and nothing else.
class DeviceFeed {
 public:
  /// `name` names the events ("<name>.sample"); fusion may be null (measured poses).
  DeviceFeed(des::Simulator& sim, std::unique_ptr<tracker::Tracker> tracker,
             std::unique_ptr<tracker::Transport> transport, std::unique_ptr<tracker::RuntimeFusion> fusion,
             const tracker::PredictionParams& prediction, const std::string& name);

  /// Schedules the reports measured in [now, end).
  void start(des::Time end);
  std::optional<tracker::TrackerSample> newest_at(des::Time t) const;
  tracker::PredictionBasis basis_of(const tracker::TrackerSample& s) const { return prediction_.basis_of(s); }
  int64_t reports() const { return reports_; }
  int64_t reports_lost() const { return lost_; }

 private:
  void measure(const tracker::TrackerSample& s);
  des::Time stamp_of(const tracker::TrackerSample& s, const tracker::Carriage& c) const;

  struct Delivered {
    des::Time at;
    tracker::TrackerSample sample;
  };
  des::Simulator& sim_;
  std::unique_ptr<tracker::Tracker> tracker_;
  std::unique_ptr<tracker::Transport> transport_;
  std::unique_ptr<tracker::RuntimeFusion> fusion_;
  tracker::HostPrediction prediction_;
  des::KindId kind_ = 0;
  des::Time end_;
  std::deque<Delivered> delivered_;  ///< visible times never decrease
  int64_t reports_ = 0, lost_ = 0;
};

}  // namespace latsim::run
