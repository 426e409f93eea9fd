// Pose prediction: estimating the head's motion from tracker samples and
// extrapolating it to the instant an image will be lit.
//
// A predictor takes the samples the host receives, in measurement order, and
// after each one holds a MotionEstimate: the pose at the newest sample's
// measurement time and its rates of change. extrapolate() carries an estimate
// forward to any target time. Keeping the estimate (a few numbers) instead of
// the predictor lets a host remember what it knew after every sample and
// answer "what would I have predicted from sample k" exactly and cheaply.
//
// Orientation is handled on the quaternion manifold: rates are world-frame
// rotation vectors (log of relative rotations, short arc) and extrapolation
// applies exp(r) to the last orientation, so a prediction is always a unit
// quaternion and never the component-wise extrapolation of q, which leaves
// the unit sphere and distorts large turns.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "latsim/des/time.hpp"
#include "latsim/tracker/pose.hpp"
#include "latsim/tracker/tracker.hpp"

namespace latsim::tracker {

/// What a predictor knows at one instant: the pose and its first and second
/// time derivatives (angular ones as world-frame rotation vectors per second).
struct MotionEstimate {
  des::Time at;  ///< the instant the estimate describes (newest sample's measurement)
  Pose pose;
  glm::dvec3 angular_velocity_rad_s{0.0};
  glm::dvec3 angular_acceleration_rad_s2{0.0};
  glm::dvec3 velocity_m_s{0.0};
  glm::dvec3 acceleration_m_s2{0.0};
};

/// The pose at `target` if the estimated rates hold: with h = target - at,
/// orientation exp(w h + a h^2 / 2) q (exact for a fixed rotation axis under
/// constant angular acceleration; for a moving axis the commutator terms of
/// order |w| |a| h^3 are left out) and position p + v h + acc h^2 / 2.
/// A negative h extrapolates backwards.
Pose extrapolate(const MotionEstimate& estimate, des::Time target);

/// The predictors `host.prediction` can name.
enum class PredictorKind { None, ConstantVelocity, ConstantAcceleration, Kalman, Fusion };

/// The scenario name of a kind ("none", "constant_velocity", "constant_acceleration", "kalman", "fusion").
std::string_view predictor_name(PredictorKind kind);
/// The kind of a scenario name; nullopt for an unknown name.
std::optional<PredictorKind> predictor_kind(std::string_view name);

/// Noise model of the Kalman filter (see KalmanPredictor for the equations).
struct KalmanParams {
  /// Process noise: the head's angular acceleration is white noise of this
  /// spectral density amplitude (deg/s^2 per sqrt(Hz)); the angular velocity
  /// then wanders by this many deg/s over one second. Larger values follow
  /// the samples more closely (less lag, less smoothing). The default gave
  /// the lowest mean prediction error on the bundled real recording at a
  /// 40 ms horizon with 0.05 and 0.2 degree tracker noise and 20 to 70
  /// tried (BENCHMARKS.md, pose prediction).
  double angular_accel_noise_deg_s2_rthz = 50.0;
  /// The same for linear acceleration, m/s^2 per sqrt(Hz); about the
  /// acceleration of a walking head over a step (not tuned on data: the
  /// bundled recording has no positions).
  double linear_accel_noise_m_s2_rthz = 2.0;
  /// Measurement noise: the tracker's covariance (orientation block for the
  /// orientation filter, position block for the position filter). A host
  /// fills this from the scenario's tracker noise unless the scenario
  /// overrides it.
  NoiseCovariance measurement_covariance = NoiseCovariance::Zero();
  /// Prior standard deviations of the velocities before any motion is seen.
  double initial_angular_speed_deg_s = 100.0;
  double initial_speed_m_s = 1.0;
};

/// How a host predicts.
struct PredictorParams {
  PredictorKind kind = PredictorKind::None;
  KalmanParams kalman;
};

/// Turns tracker samples into motion estimates.
class Predictor {
 public:
  virtual ~Predictor() = default;
  /// Takes the next sample. Samples must come in strictly increasing
  /// measurement time (the tracker guarantees it); an earlier or equal time
  /// throws std::logic_error.
  virtual void observe(const TrackerSample& sample) = 0;
  /// The estimate after the samples observed so far (nullopt before the first).
  virtual std::optional<MotionEstimate> estimate() const = 0;
  virtual PredictorKind kind() const = 0;
  /// A copy of this predictor in its current state.
  virtual std::unique_ptr<Predictor> clone() const = 0;
};

/// A predictor of the given kind. Throws std::invalid_argument for Kalman
/// parameters that are not positive and finite or a measurement covariance
/// that is not symmetric positive semidefinite.
std::unique_ptr<Predictor> make_predictor(const PredictorParams& params);

}  // namespace latsim::tracker
