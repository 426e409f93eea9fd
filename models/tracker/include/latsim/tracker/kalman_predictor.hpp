// A Kalman filter on head orientation and angular velocity, and on position
// and velocity, for pose prediction.
#pragma once

#include <optional>

#include <Eigen/Core>

#include "latsim/tracker/predictor.hpp"

namespace latsim::tracker {

/// Filters noisy tracker samples under a constant-velocity motion model and
/// predicts by running the model forward.
///
/// Two independent filters with the same structure (cross-covariance between
/// position and orientation noise is ignored):
///
/// - Orientation: an error-state (multiplicative) filter. The nominal state is
///   a unit quaternion q and a world-frame angular velocity w; the error state
///   is x = [dtheta, dw] with q_true = exp(dtheta) q. Between samples, dt
///   apart, q <- exp(w dt) q and w <- w; the error transition is, to first
///   order in |w| dt, F = [[R(w dt), dt I], [0, I]] with R the rotation matrix
///   of w dt. The measurement is the sampled quaternion z = exp(n) q_true with
///   n ~ N(0, R_meas) (exactly the tracker's noise model); the innovation is
///   y = log(z q^-1) on the short arc, H = [I 0].
/// - Position: the same with p, v, F = [[I, dt I], [0, I]], y = z - p.
///
/// Process noise is the continuous white-noise-acceleration model: the
/// acceleration is white with spectral density s (rad^2/s^3 or m^2/s^3), so
/// per interval Q = s [[dt^3/3 I, dt^2/2 I], [dt^2/2 I, dt I]], which is
/// exact for any dt and makes unequal (jittered) intervals and microsecond
/// spacing need nothing special. The update uses the Joseph form and keeps P
/// symmetric, so it stays positive semidefinite over hours of samples and
/// with a noise-free tracker (R_meas = 0, when the filter follows the samples
/// exactly and only smooths the velocity).
///
/// The first sample sets the pose with covariance R_meas and zero velocity
/// with the prior variance of KalmanParams. Under this model a constant
/// velocity is tracked with zero steady-state bias; the estimate's
/// accelerations are zero, so extrapolate() continues at constant velocity.
class KalmanPredictor final : public Predictor {
 public:
  using Matrix6 = Eigen::Matrix<double, 6, 6>;

  /// Throws std::invalid_argument for non-positive or non-finite noise
  /// densities or prior speeds, or a measurement covariance that is not
  /// symmetric positive semidefinite.
  explicit KalmanPredictor(const KalmanParams& params);

  void observe(const TrackerSample& sample) override;
  std::optional<MotionEstimate> estimate() const override { return estimate_; }
  PredictorKind kind() const override { return PredictorKind::Kalman; }
  std::unique_ptr<Predictor> clone() const override { return std::make_unique<KalmanPredictor>(*this); }

  /// Posterior error covariances after the newest sample: orientation
  /// [dtheta (rad), dw (rad/s)] and position [dp (m), dv (m/s)].
  const Matrix6& orientation_covariance() const { return orientation_p_; }

 private:
  void start(const TrackerSample& sample);

  Eigen::Matrix3d orientation_r_;
  Eigen::Matrix3d position_r_;
  double angular_psd_;
  double linear_psd_;
  double angular_prior_var_;
  double linear_prior_var_;
  Matrix6 orientation_p_ = Matrix6::Zero();
  Matrix6 position_p_ = Matrix6::Zero();
  std::optional<MotionEstimate> estimate_;
  int64_t last_index_ = 0;
};

}  // namespace latsim::tracker
