// Prediction by extrapolating finite differences of the newest samples.
#pragma once

#include <array>
#include <optional>

#include "latsim/tracker/predictor.hpp"

namespace latsim::tracker {

/// Holds (order 0), or extrapolates at constant velocity (order 1) or
/// constant acceleration (order 2) from the newest one, two or three samples.
///
/// Velocities are divided differences over the true sample intervals, so
/// jittered, unequal intervals need no special care: with samples at t0 < t1
/// < t2, w01 = log(q1 q0^-1) / (t1 - t0) is the exact mean angular velocity
/// over [t0, t1] and belongs to its midpoint; the angular acceleration is
/// (w12 - w01) / ((t2 - t0) / 2), and the velocity at t2 is w12 + acc (t2 -
/// t1) / 2. Position uses the same formulas on p. Constant velocity is
/// therefore exact for a constant-rate turn and constant acceleration for any
/// motion whose angle about a fixed axis (or whose position) is quadratic in
/// time, at any spacing. Before enough samples have arrived the order drops
/// (one sample: hold; two: constant velocity).
///
/// Every relative rotation is taken on the short arc, so a sign flip between
/// samples changes nothing, and a turn of more than 180 degrees between two
/// samples is seen as the shorter turn the other way (the samples cannot
/// tell them apart).
class ExtrapolatingPredictor final : public Predictor {
 public:
  /// `order` 0, 1 or 2; anything else throws std::invalid_argument.
  explicit ExtrapolatingPredictor(int order);

  void observe(const TrackerSample& sample) override;
  std::optional<MotionEstimate> estimate() const override { return estimate_; }
  PredictorKind kind() const override;
  std::unique_ptr<Predictor> clone() const override { return std::make_unique<ExtrapolatingPredictor>(*this); }

 private:
  void update_estimate();

  int order_;
  std::array<TrackerSample, 3> recent_{};  ///< newest last; the first 3 - count_ unused
  int count_ = 0;
  std::optional<MotionEstimate> estimate_;
};

}  // namespace latsim::tracker
