// What the results of a run are computed from: the images a pipeline shows
// (their poses and the times of their stages) and the host's view of the
// tracker, through which every pose of an image is taken.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include "latsim/des/time.hpp"
#include "latsim/tracker/host_prediction.hpp"
#include "latsim/tracker/pose.hpp"
#include "latsim/tracker/tracker.hpp"

namespace latsim::results {

/// One image a pipeline puts in a front buffer: the pose it was computed from
/// and when each stage ran. Registered with the recorder before presenting.
struct ImageRecord {
  int64_t frame = -1;                 ///< pipeline's frame (or field) number
  int eye = 0;
  tracker::TrackerSample sample;      ///< the newest sample the pose came from (latency origin)
  des::Time host_received;            ///< when the host could first see that sample
  des::Time render_start;             ///< rendering latency starts here
  des::Time render_end;
  /// The instant the head pose was predicted for (the pipeline's expected
  /// photon time, or the sample's time plus a fixed horizon) and that pose;
  /// without prediction it is the sample's own pose.
  des::Time predicted_for;
  tracker::Pose head_pose;
  tracker::Pose eye_pose;             ///< the eye pose the image was rendered from
  /// Address recalculation: orientation is taken from the newest sample at
  /// scanout, so rotation and translation latency differ.
  bool orientation_at_scanout = false;
  /// Time warp: the image is an image rendered from `source_pose` re-projected
  /// to `eye_pose`. A rotation-only warp keeps the source's position: its
  /// orientation was measured at `orientation_measured_at`, later than `sample`.
  enum class Warp : uint8_t { none, rotation, positional };
  Warp warp = Warp::none;
  tracker::Pose source_pose;
  des::Time orientation_measured_at;
  /// A later strip of a refresh's image (continuous time warp): its latency
  /// is its own, but it is not another image in the frame rate.
  bool continues_image = false;
  /// `frame` numbers the application's frames (FrameRecorder's): false for
  /// images a compositor renders itself (beam racing), numbered by warp.
  bool shows_app_frame = true;
  /// A tracked controller (/controller): the pose the image draws it at,
  /// predicted like the head's for the image's render, and when that pose
  /// was measured. Absent without a controller.
  std::optional<tracker::Pose> controller_pose;
  des::Time controller_measured_at;
};

/// Newest tracker data available to the host at any instant.
class HostFeed {
 public:
  virtual ~HostFeed() = default;
  /// Newest sample the host application can see at time t (nullopt before the first).
  virtual std::optional<tracker::TrackerSample> newest_at(des::Time t) const = 0;
  /// When that sample became visible to the host.
  virtual des::Time received_at(const tracker::TrackerSample& s) const = 0;
  /// Called whenever a new sample becomes visible to the host (async senders).
  virtual void on_delivery(std::function<void(const tracker::TrackerSample&, des::Time)> fn) = 0;
  /// What the host knew when `s` was its newest sample: enough to predict
  /// the pose for any photon time. `s` must be recent (the host keeps about
  /// one second); pipelines that hold a sample longer keep its basis.
  virtual tracker::PredictionBasis basis_of(const tracker::TrackerSample& s) const = 0;
  /// Whether the scenario asks the host to predict (/host/prediction).
  virtual bool predicts() const = 0;
  /// The tracked controller's pose for an image computed from the head pose
  /// `head`: the controller measured with `head.sample`, predicted by the
  /// host's predictor to the same instant. nullopt without a controller.
  virtual std::optional<tracker::PosePrediction> controller_for(const tracker::PosePrediction& head) const {
    (void)head;
    return std::nullopt;
  }

  /// The pose for an image computed at `now` that the pipeline expects to be
  /// lit at `photon_time`: the newest sample visible at `now`, predicted by
  /// the host's predictor to `photon_time` (or to its fixed horizon; the
  /// sample's pose when the host does not predict). nullopt before the first
  /// sample. Every pipeline takes the pose of an image (or line, or pixel)
  /// through this call.
  std::optional<tracker::PosePrediction> pose_for(des::Time now, des::Time photon_time) const {
    const std::optional<tracker::TrackerSample> s = newest_at(now);
    if (!s) return std::nullopt;
    tracker::PosePrediction p = basis_of(*s).for_photon_time(photon_time);
    p.read_at = now;
    return p;
  }
};

}  // namespace latsim::results
