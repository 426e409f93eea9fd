// The host's view of the tracker: the newest sample it can see at any
// instant, and the pose it predicts from it for an image. Implemented by the
// run's tracker host; read by the pipelines, the recorders and frame capture.
#pragma once

#include <functional>
#include <optional>

#include "latsim/des/time.hpp"
#include "latsim/tracker/host_prediction.hpp"
#include "latsim/tracker/tracker.hpp"

namespace latsim::tracker {

/// Newest tracker data available to the host at any instant.
class HostFeed {
 public:
  virtual ~HostFeed() = default;
  /// Newest sample the host application can see at time t (nullopt before the first).
  virtual std::optional<TrackerSample> newest_at(des::Time t) const = 0;
  /// When that sample became visible to the host.
  virtual des::Time received_at(const TrackerSample& s) const = 0;
  /// Called whenever a new sample becomes visible to the host (async senders).
  virtual void on_delivery(std::function<void(const TrackerSample&, des::Time)> fn) = 0;
  /// What the host knew when `s` was its newest sample: enough to predict
  /// the pose for any photon time. `s` must be recent (the host keeps about
  /// one second); pipelines that hold a sample longer keep its basis.
  virtual PredictionBasis basis_of(const TrackerSample& s) const = 0;
  /// Whether the scenario asks the host to predict (/host/prediction).
  virtual bool predicts() const = 0;
  /// The tracked controller's pose for an image computed from the head pose
  /// `head`: the controller measured with `head.sample`, predicted by the
  /// host's predictor to the same instant. nullopt without a controller.
  virtual std::optional<PosePrediction> controller_for(const PosePrediction& head) const {
    (void)head;
    return std::nullopt;
  }

  /// The pose for an image computed at `now` that the pipeline expects to be
  /// lit at `photon_time`: the newest sample visible at `now`, predicted by
  /// the host's predictor to `photon_time` (or to its fixed horizon; the
  /// sample's pose when the host does not predict). nullopt before the first
  /// sample. Every pipeline takes the pose of an image (or line, or pixel)
  /// through this call.
  std::optional<PosePrediction> pose_for(des::Time now, des::Time photon_time) const {
    const std::optional<TrackerSample> s = newest_at(now);
    if (!s) return std::nullopt;
    PosePrediction p = basis_of(*s).for_photon_time(photon_time);
    p.read_at = now;
    return p;
  }
};

}  // namespace latsim::tracker
