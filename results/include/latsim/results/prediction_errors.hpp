// How far each of the host's predictions was off.
#pragma once

#include "latsim/results/figure_writer.hpp"
#include "latsim/results/image_record.hpp"
#include "latsim/results/phase_split.hpp"
#include "latsim/stats/stats.hpp"
#include "latsim/tracker/host_prediction.hpp"
#include "latsim/tracker/motion_source.hpp"

namespace latsim::results {

/// Turns each prediction an image, a looked-up line or a frameless pixel was
/// drawn with into prediction_horizon_ms, prediction_error_deg (split by
/// motion phase when the run asks) and prediction_error_mm, judged against
/// the true head at the instant predicted for. Only when the scenario
/// predicts (/host/prediction).
class PredictionErrors {
 public:
  PredictionErrors(FigureWriter figures, const tracker::MotionSource& motion)
      : figures_(std::move(figures)), motion_(motion) {}

  void enable(bool on) { on_ = on; }
  bool on() const { return on_; }
  void split_by(MotionPhases* phases) { phases_ = phases; }

  /// One prediction: its error against the truth at its target, in degrees
  /// (when `orientation`) and millimetres (when `position`), and its horizon.
  void pose_predicted(const tracker::PosePrediction& prediction, bool orientation, bool position);
  /// An image of eye 0 first shown: what it was predicted from, for when, and
  /// how far off (stereo pairs share one head pose).
  void image_shown(const ImageRecord& img);

 private:
  FigureWriter figures_;
  const tracker::MotionSource& motion_;
  bool on_ = false;
  MotionPhases* phases_ = nullptr;
  stats::Distribution* horizon_ = nullptr;
  stats::Distribution* deg_ = nullptr;
  stats::Distribution* mm_ = nullptr;
  PhaseSplit split_{"prediction_error_deg"};
};

}  // namespace latsim::results
