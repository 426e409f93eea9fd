// What a viewer or a camera sees: apparent latency, the simulated camera rig
// and the tracked controller, computed at the end of the run from the
// orientations shown at one pixel per refresh.
#pragma once

#include <optional>
#include <span>
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "latsim/des/time.hpp"
#include "latsim/display/display.hpp"
#include "latsim/display/raster_timing.hpp"
#include "latsim/measurement/apparent_latency.hpp"
#include "latsim/measurement/camera_rig.hpp"
#include "latsim/measurement/shown_trace.hpp"
#include "latsim/results/figure_writer.hpp"
#include "latsim/results/image_record.hpp"
#include "latsim/tracker/motion_phase.hpp"
#include "latsim/tracker/motion_source.hpp"

namespace latsim::results {

/// Keeps, one sample per refresh, the orientation shown at the centre of
/// eye 0's display (and at the camera rig's display point), and at the end
/// turns them into apparent_latency_ms, the rig's measured_latency_ms and
/// the controller's latencies. Keeps nothing unless the scenario asks.
class SeenFigures {
 public:
  SeenFigures(FigureWriter figures, const tracker::MotionSource& motion, const display::RasterTiming& timing)
      : figures_(std::move(figures)), motion_(motion), timing_(timing) {}

  /// Apparent latency (split by the motion phases of `phases`) and
  /// prediction_catch_up_ms.
  void measure_apparent_latency(const measurement::ApparentLatencyParams& params,
                                const tracker::MotionPhaseParams& phases);
  /// Films the rig's display point and the true head with a camera whose
  /// frames open at `camera`.
  void film(const measurement::CameraRigParams& params, const des::PeriodicSchedule& camera);
  /// A tracked controller moving as `motion` (which must outlive this):
  /// controller_latency_ms and, with apparent latency,
  /// controller_apparent_latency_ms; the rig films it when its object is
  /// the controller.
  void track_controller(const tracker::MotionSource& motion);
  /// The display's persistence (the display's, read, never recomputed): the
  /// rig's camera sees each new value along the panel's transition.
  void set_persistence(const display::Persistence* persistence) { persistence_ = persistence; }

  /// Whether a span of eye 0 may light a kept pixel.
  bool wants(const display::ScanoutSpan& span) const { return traces_ != 0 && span.eye == 0; }
  /// The orientation a span of eye 0 shows (and the controller of its image),
  /// for the kept pixels it lights.
  void shown(const display::ScanoutSpan& span, const glm::dquat& orientation, const ImageRecord& img);
  /// The figures, once the run has ended at `duration`.
  void finish(des::Time duration);

 private:
  /// The shown trace at the centre of eye 0's display, kept once for apparent
  /// latency and the controller alike.
  void keep_centre_trace();
  /// Apparent latency of `shown` against `truth`, as figures named `prefix` + apparent_latency_ms ....
  void apparent_figures(const std::string& prefix, std::span<const measurement::ShownSample> shown,
                        const tracker::MotionSource& truth);
  /// The camera rig filming `truth` and the angles `shown` at its display point.
  void rig_figures(std::span<const measurement::ShownSample> shown, const tracker::MotionSource& truth,
                   des::Time duration);

  FigureWriter figures_;
  const tracker::MotionSource& motion_;
  const display::RasterTiming& timing_;
  int traces_ = 0;
  std::optional<measurement::ShownTrace> centre_trace_;
  std::optional<measurement::ApparentLatencyParams> apparent_;
  const tracker::MotionSource* controller_ = nullptr;
  const display::Persistence* persistence_ = nullptr;
  tracker::MotionPhaseParams apparent_phases_;
  std::optional<measurement::ShownTrace> rig_trace_;
  measurement::CameraRigParams rig_;
  des::PeriodicSchedule camera_;
};

}  // namespace latsim::results
