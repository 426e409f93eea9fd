#include "latsim/tracker/fusion_predictor.hpp"

#include <stdexcept>
#include <string>

namespace latsim::tracker {

void FusionPredictor::observe(const TrackerSample& sample) {
  if (estimate_ && sample.measured_at <= estimate_->at)
    throw std::logic_error("predictor samples must come in increasing measurement time (sample " +
                           std::to_string(sample.index) + ")");
  MotionEstimate e;
  e.at = sample.measured_at;
  e.pose = sample.pose;
  e.angular_velocity_rad_s = sample.angular_velocity_rad_s.value_or(glm::dvec3(0.0));
  e.velocity_m_s = sample.velocity_m_s;
  estimate_ = e;
}

}  // namespace latsim::tracker
