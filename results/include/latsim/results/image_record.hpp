// What the results of a run are computed from: the images a pipeline shows
// (their poses and the times of their stages). Every pose of an image is
// taken through the host's view of the tracker (tracker::HostFeed).
#pragma once

#include <cstdint>
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

}  // namespace latsim::results
