// Prediction from the runtime's own fusion state: its orientation and
// position, carried forward at the angular velocity and velocity it holds.
#pragma once

#include <optional>

#include "latsim/tracker/predictor.hpp"

namespace latsim::tracker {

/// Extrapolates each fused sample (an IMU chain's report after the
/// runtime's fusion) at the fusion's own angular velocity, the newest
/// bias-corrected gyro rate, and its reference-derived velocity: constant
/// velocity from the filter's state, as headset runtimes describe their
/// prediction (LaValle et al. 2014: the gyro's current rate held over the
/// horizon). A sample without a fusion state (a measured pose) is held.
class FusionPredictor final : public Predictor {
 public:
  void observe(const TrackerSample& sample) override;
  std::optional<MotionEstimate> estimate() const override { return estimate_; }
  PredictorKind kind() const override { return PredictorKind::Fusion; }
  std::unique_ptr<Predictor> clone() const override { return std::make_unique<FusionPredictor>(*this); }

 private:
  std::optional<MotionEstimate> estimate_;
};

}  // namespace latsim::tracker
