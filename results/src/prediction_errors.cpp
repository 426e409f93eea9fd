#include "latsim/results/prediction_errors.hpp"

#include "latsim/tracker/pose.hpp"
#include "latsim/units/units.hpp"

namespace latsim::results {

void PredictionErrors::pose_predicted(const tracker::PosePrediction& p, bool orientation, bool position) {
  const tracker::Pose truth = motion_.pose_at(p.target);
  figures_.add(horizon_, "prediction_horizon_ms", p.horizon().to_ms());
  if (orientation) {
    const double deg = units::rad_to_deg(tracker::angle_between(p.pose.orientation, truth.orientation));
    figures_.add(deg_, "prediction_error_deg", deg);
    split_.add(phases_, figures_, deg, p.target);
  }
  if (position)
    figures_.add(mm_, "prediction_error_mm", glm::length(p.pose.position_m - truth.position_m) * 1e3);
}

void PredictionErrors::image_shown(const ImageRecord& img) {
  // Address recalculation replaces the orientation at scanout, so only its
  // position counts here. A rotation warp's prediction is the warp's own:
  // its orientation, from the warp's sample to the warp's target (the
  // position it keeps was predicted by the application for another instant,
  // and is not judged here).
  if (!on_ || img.eye != 0) return;
  tracker::PosePrediction p{img.sample, img.predicted_for, img.head_pose};
  const bool rotation_warp = img.warp == ImageRecord::Warp::rotation;
  if (rotation_warp) p.sample.measured_at = img.orientation_measured_at;
  pose_predicted(p, !img.orientation_at_scanout, !rotation_warp);
}

}  // namespace latsim::results
