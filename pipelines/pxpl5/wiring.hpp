// The two Pixel-Planes 5 pipelines, "pxpl5_rc" (Rendering Control) and
// "pxpl5_slats" (Slats), and the wiring they share between the pxpl5 engines
// and a run.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "latsim/stats/stats.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/pxpl5/engine_hooks.hpp"
#include "latsim/pxpl5/field_timing.hpp"
#include "latsim/pxpl5/hardware.hpp"
#include "latsim/pxpl5/workload.hpp"

namespace latsim::pipelines {

/// Where the triangles of each image come from.
enum class Pxpl5WorkloadKind {
  synthetic,  ///< /scene's `triangles` and `regions_per_triangle`, the same for every image (calibration)
  view,       ///< /scene's geometry inside each eye's view at the pose the image uses
};

/// A per-item cost whose item count the view workload learns only from the
/// scene's geometry: checked with scenario::check_span_at when the workload is
/// built, before the first event.
struct Pxpl5ViewSpan {
  std::string pointer;       ///< the cost's key, e.g. /pipeline/transform_us_per_triangle
  double per_item_s = 0.0;
  bool per_eye = false;      ///< items are counted once per eye (Rendering Control), not once for both (Slats)
  bool per_region = false;   ///< and in every region (the most a triangle can touch)
  bool spheres = false;      ///< items are the spheres, not the triangles
};

/// What both pipelines read besides their own costs.
struct Pxpl5Common {
  bool stereo = true;
  Pxpl5WorkloadKind workload = Pxpl5WorkloadKind::synthetic;
  pxpl5::Workload synthetic;
  std::vector<Pxpl5ViewSpan> view_spans;  ///< workload view: what one image costs must fit the run's clock
  bool draws_spheres = false;             ///< the pipeline has sphere primitives (Rendering Control)
  bool cull_back_faces = false;           ///< workload view: back-facing triangles are rejected
};

/// Declares the /pipeline keys both Pixel-Planes 5 pipelines share.
void bind_hardware(scenario::Section& s, pxpl5::HardwareParams& p);
/// Declares `workload` and what both read from the shared sections: stereo and
/// the /scene workload (both required).
void bind_pxpl5_common(scenario::Section& s, const sections::SharedParams& shared, const pxpl5::HardwareParams& hw,
                       Pxpl5Common& common);

/// Connects a pxpl5 engine to a run: host samples in, images to the recorder
/// and display, stage intervals to the timeline, named samples to figures.
class Pxpl5Wiring {
 public:
  explicit Pxpl5Wiring(RunContext& ctx);
  Pxpl5Wiring(const Pxpl5Wiring&) = delete;
  Pxpl5Wiring& operator=(const Pxpl5Wiring&) = delete;

  /// The display's retraces and beam, as the engines see them.
  pxpl5::FieldTiming field_timing() const;
  /// The display's screen in 128 x 128 renderer regions.
  pxpl5::RegionGrid grid() const;
  /// The workload the scenario asks for (valid while this wiring lives).
  pxpl5::WorkloadSource& workload(const Pxpl5Common& common);
  /// Hooks that feed this wiring; valid while it lives.
  pxpl5::EngineHooks hooks();
  /// When an image whose pose is taken at time t is expected to be lit: each
  /// pipeline's own horizon (set before the engine starts).
  void expect_photon_time(std::function<des::Time(des::Time)> fn) { expected_photon_time_ = std::move(fn); }
  /// The pose the host gives an image computed from `sample` (its newest) at
  /// time t, predicted to the expected photon time, remembered under a new token.
  int64_t remember(const tracker::TrackerSample& sample, des::Time t);
  /// From a frame's pose read to the last COPY of its last eye, as observed
  /// for the newest finished frame (zero before the first).
  des::Time read_to_copy_end() const { return read_to_copy_end_; }
  /// Whether the host has sent the processors viewing transforms yet.
  bool transforms_sent() const { return transforms_sent_; }
  /// Reports the collected distributions and utilisation to the recorder.
  void report(const pxpl5::Utilisation& utilisation, int64_t frames_completed) const;

 private:
  void present(const pxpl5::FrameReady& frame);
  void region_written(const pxpl5::RegionWrite& write);
  /// The recorder's id of an image (registered on first use), -1 without a sample.
  int64_t image_id(int64_t frame, const pxpl5::EyeImage& image);
  tracker::Pose eye_pose_of_token(int64_t token, int eye) const;

  RunContext* ctx_;
  std::function<des::Time(des::Time)> expected_photon_time_;
  std::map<int64_t, tracker::PosePrediction> poses_;  // by token, recent samples' only
  int64_t next_token_ = 0;
  des::Time read_to_copy_end_;
  std::map<std::string, stats::Distribution> samples_by_name_;
  std::map<std::pair<int64_t, int>, int64_t> image_ids_;  // (frame, eye) -> recorder id, recent ones only
  std::unique_ptr<pxpl5::WorkloadSource> workload_;
  int64_t images_without_sample_ = 0;
  bool transforms_sent_ = false;
};

}  // namespace latsim::pipelines
