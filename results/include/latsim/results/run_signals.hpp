// What a pipeline tells the recorders besides the spans the display scans
// out: signals it emits as things happen, which the listeners of each figure
// family turn into figures.
#pragma once

#include <glm/glm.hpp>

#include "latsim/des/time.hpp"
#include "latsim/results/image_figures.hpp"
#include "latsim/results/prediction_errors.hpp"
#include "latsim/results/registration_errors.hpp"
#include "latsim/results/span_latencies.hpp"
#include "latsim/tracker/host_prediction.hpp"
#include "latsim/tracker/tracker.hpp"

namespace latsim::results {

/// The signals a pipeline emits, each delivered to the listener whose
/// figures it feeds.
class RunSignals {
 public:
  RunSignals(SpanLatencies& latencies, ImageFigures& images, RegistrationErrors& registration,
             PredictionErrors& prediction)
      : latencies_(latencies), images_(images), registration_(registration), prediction_(prediction) {}

  /// The pipeline shows whole images (frame_rate_hz; a run showing none is warned about).
  void shows_images() { images_.shows_images(); }
  /// A render began that the pipeline means to show by the first refresh at
  /// or after `due_by` (missed_refreshes).
  void image_due(des::Time due_by) { images_.image_due(due_by); }
  /// A pixel lit at `photon` with a colour computed wholly from sample `s`
  /// (frameless rendering).
  void pixel_lit(const tracker::TrackerSample& s, des::Time photon) { latencies_.pixel_lit(s, photon); }
  /// A sampled pixel of a whole image computed from `s`, lit at `photon` (pixel_age_ms).
  void pixel_shown(const tracker::TrackerSample& s, des::Time photon) { latencies_.pixel_age(s, photon); }
  /// World point `point_m` drawn along head-frame direction `drawn_head_dir`
  /// of eye `eye`, lit at `photon` (registration error).
  void point_drawn(int eye, const glm::dvec3& point_m, const glm::dvec3& drawn_head_dir, des::Time photon) {
    registration_.point_drawn(eye, point_m, drawn_head_dir, photon);
  }
  /// A pose the host predicted and the pipeline drew with (prediction error
  /// of its orientation and of its position, as asked).
  void pose_predicted(const tracker::PosePrediction& p, bool orientation, bool position) {
    prediction_.pose_predicted(p, orientation, position);
  }

 private:
  SpanLatencies& latencies_;
  ImageFigures& images_;
  RegistrationErrors& registration_;
  PredictionErrors& prediction_;
};

}  // namespace latsim::results
