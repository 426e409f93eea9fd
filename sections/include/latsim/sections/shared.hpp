// The scenario's shared sections — everything but /pipeline — as typed
// structs, each key declared once in the bindings of this library.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "latsim/des/clock.hpp"
#include "latsim/display/params.hpp"
#include "latsim/measurement/apparent_latency.hpp"
#include "latsim/measurement/camera_rig.hpp"
#include "latsim/renderer/scene_spec.hpp"
#include "latsim/scenario/section.hpp"
#include "latsim/tracker/motion_and_transport.hpp"
#include "latsim/tracker/host_prediction.hpp"
#include "latsim/tracker/motion_phase.hpp"
#include "latsim/tracker/tracker.hpp"

namespace latsim::sections {

/// /host: the application's view of the head.
struct HostParams {
  bool stereo = false;
  double ipd_m = 0.064;
  /// /host/prediction: how the host predicts poses (none when absent).
  std::optional<tracker::PredictionParams> prediction;
};

/// /scene: the geometry frames and address recalculation draw, and the
/// workload that rendering costs are computed from.
struct SceneParams {
  renderer::SceneSpec geometry;
  int64_t triangles = 0;
  double coverage = 1.0;
  double regions_per_triangle = 1.3;
};

/// /probes: world points whose registration error is measured.
struct ProbeParams {
  std::vector<glm::dvec3> points_m;
};

/// /output: what a run keeps besides its figures.
struct OutputParams {
  bool keep_samples = false;
  bool timeline = true;
  int64_t timeline_max_entries = 200000;
};

/// /frames: which displayed fields are ray-cast and written as images.
struct FramesParams {
  bool enabled = true;
  std::vector<double> at_s;
  int64_t every_nth_refresh = 0;
  int64_t max_captures = 20;
  int eye = 0;
  int threads = 1;
  glm::vec3 background{0.0f};
  double diff_gain = 4.0;
  double age_scale_ms = 100.0;
};

/// /controller: a handheld controller, tracked with the head and drawn by the
/// pipeline.
struct ControllerParams {
  tracker::MotionParams motion;
  /// /controller/tracker: a chain of its own (absent: measured with the head's samples).
  std::optional<tracker::TrackerParams> tracker;
  /// /controller/transport: its link to the host (with a tracker of its own).
  tracker::TransportParams transport;
};

/// Every section of a scenario that the run builds for any pipeline.
struct SharedParams {
  std::string description;
  double duration_s = 10.0;
  int64_t seed = 1;
  tracker::MotionParams motion;
  /// /controller: a tracked handheld controller (none when absent).
  std::optional<ControllerParams> controller;
  tracker::TrackerParams tracker;
  tracker::TransportParams transport;
  HostParams host;
  display::DisplayParams display;
  std::optional<SceneParams> scene;
  std::optional<ProbeParams> probes;
  OutputParams output;
  std::optional<FramesParams> frames;
  /// /motion_phases: split figures by motion phase (not split when absent).
  std::optional<tracker::MotionPhaseParams> motion_phases;
  /// /apparent_latency: the shift aligning the shown movement with the true one (not computed when absent).
  std::optional<measurement::ApparentLatencyParams> apparent_latency;
  /// /measurement: a simulated camera rig (none when absent).
  std::optional<measurement::CameraRigParams> measurement;
};

/// Declares (and reads) every top-level key except /pipeline.
void bind(scenario::Section& s, SharedParams& p);

void bind(scenario::Section& s, tracker::MotionParams& p);
void bind(scenario::Section& s, tracker::TrackerParams& p);
/// /tracker/imu (params/src/imu_chain.cpp).
void bind(scenario::Section& s, tracker::ImuChainParams& p);
/// /controller/tracker and /controller/transport: the controller's own chain.
void bind_controller_chain(scenario::Section& s, ControllerParams& p);
void bind(scenario::Section& s, tracker::TransportParams& p);
void bind(scenario::Section& s, display::DisplayParams& p);
void bind(scenario::Section& s, SceneParams& p);
/// /host/prediction; the Kalman filter's noise defaults to `tracker`'s.
void bind(scenario::Section& s, tracker::PredictionParams& p, const tracker::TrackerParams& tracker);
void bind(scenario::Section& s, tracker::MotionPhaseParams& p);
void bind(scenario::Section& s, measurement::ApparentLatencyParams& p);
/// /measurement, or a pipeline's rig with its keys. `head_only`: empty when the
/// scenario tracks a controller (it may be filmed), else why `object` can only
/// be the head there (the one-line error for `controller`).
void bind(scenario::Section& s, measurement::CameraRigParams& p, std::string_view head_only);

/// A clock's `<prefix>phase_ms` (absent: drawn per replication, uniformly
/// over one period, from the clock's own stream) and `<prefix>rate_error_ppm`.
void clock(scenario::Section& s, std::string_view prefix, des::ClockSettings& c, std::string_view what);

/// Three numbers [x, y, z].
void vec3(scenario::Section& s, std::string_view key, glm::dvec3& v, scenario::KeySpec spec);
/// A linear colour [r, g, b].
void colour(scenario::Section& s, std::string_view key, glm::vec3& v, scenario::KeySpec spec);

}  // namespace latsim::sections
