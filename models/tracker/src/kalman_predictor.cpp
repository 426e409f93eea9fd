#include "latsim/tracker/kalman_predictor.hpp"
#include "latsim/units/units.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>

namespace latsim::tracker {

namespace {

using Matrix6 = KalmanPredictor::Matrix6;
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix3 = Eigen::Matrix3d;
using Vector3 = Eigen::Vector3d;


Vector3 to_eigen(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
glm::dvec3 to_glm(const Vector3& v) { return {v(0), v(1), v(2)}; }

Matrix3 rotation_matrix(const glm::dquat& q) {
  const glm::dmat3 m = glm::mat3_cast(q);
  Matrix3 r;
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) r(row, col) = m[col][row];  // glm is column-major
  return r;
}

double positive(double v, const char* what) {
  if (!std::isfinite(v) || v <= 0.0)
    throw std::invalid_argument(std::string("Kalman ") + what + " must be positive and finite (got " +
                                std::to_string(v) + ")");
  return v;
}

/// P <- F P F^T + Q for the constant-velocity model over dt seconds, with
/// `rotation` the transition of the pose error (identity for position).
void predict_covariance(Matrix6& p, const Matrix3& rotation, double dt, double psd) {
  Matrix6 f = Matrix6::Identity();
  f.topLeftCorner<3, 3>() = rotation;
  f.topRightCorner<3, 3>() = dt * Matrix3::Identity();
  Matrix6 q = Matrix6::Zero();
  const Matrix3 i3 = Matrix3::Identity();
  q.topLeftCorner<3, 3>() = (psd * dt * dt * dt / 3.0) * i3;
  q.topRightCorner<3, 3>() = (psd * dt * dt / 2.0) * i3;
  q.bottomLeftCorner<3, 3>() = (psd * dt * dt / 2.0) * i3;
  q.bottomRightCorner<3, 3>() = (psd * dt) * i3;
  p = f * p * f.transpose() + q;
  p = (0.5 * (p + p.transpose())).eval();
}

/// Measurement update with H = [I 0]: returns the error-state correction
/// K y and leaves the posterior covariance in p (Joseph form, symmetrised).
Vector6 update(Matrix6& p, const Vector3& innovation, const Matrix3& r) {
  const Matrix3 s = p.topLeftCorner<3, 3>() + r;
  const Eigen::LDLT<Matrix3> ldlt(s);
  // K = P H^T S^-1, and S is symmetric, so K^T = S^-1 (H P).
  const Eigen::Matrix<double, 6, 3> k = ldlt.solve(p.topRows<3>()).transpose();
  if (ldlt.info() != Eigen::Success || !k.allFinite())
    throw std::logic_error("Kalman innovation covariance is singular");
  Matrix6 i_kh = Matrix6::Identity();
  i_kh.leftCols<3>() -= k;
  p = i_kh * p * i_kh.transpose() + k * r * k.transpose();
  p = (0.5 * (p + p.transpose())).eval();
  return k * innovation;
}

}  // namespace

KalmanPredictor::KalmanPredictor(const KalmanParams& params)
    : orientation_r_(params.measurement_covariance.bottomRightCorner<3, 3>()),
      position_r_(params.measurement_covariance.topLeftCorner<3, 3>()),
      angular_psd_(std::pow(positive(params.angular_accel_noise_deg_s2_rthz, "angular acceleration noise") *
                                units::kRadPerDeg,
                            2)),
      linear_psd_(std::pow(positive(params.linear_accel_noise_m_s2_rthz, "linear acceleration noise"), 2)),
      angular_prior_var_(std::pow(positive(params.initial_angular_speed_deg_s, "initial angular speed") * units::kRadPerDeg, 2)),
      linear_prior_var_(std::pow(positive(params.initial_speed_m_s, "initial speed"), 2)) {
  // Validates symmetry and semidefiniteness with the tracker's own rules.
  (void)noise_factor(params.measurement_covariance);
}

void KalmanPredictor::start(const TrackerSample& sample) {
  MotionEstimate e;
  e.at = sample.measured_at;
  e.pose = Pose{sample.pose.position_m, glm::normalize(sample.pose.orientation)};
  estimate_ = e;
  orientation_p_.setZero();
  orientation_p_.topLeftCorner<3, 3>() = orientation_r_;
  orientation_p_.bottomRightCorner<3, 3>() = angular_prior_var_ * Matrix3::Identity();
  position_p_.setZero();
  position_p_.topLeftCorner<3, 3>() = position_r_;
  position_p_.bottomRightCorner<3, 3>() = linear_prior_var_ * Matrix3::Identity();
}

void KalmanPredictor::observe(const TrackerSample& sample) {
  if (!estimate_) {
    start(sample);
    last_index_ = sample.index;
    return;
  }
  MotionEstimate& e = *estimate_;
  if (sample.measured_at <= e.at)
    throw std::logic_error("predictor samples must come in increasing measurement time (sample " +
                           std::to_string(sample.index) + " is not later than sample " +
                           std::to_string(last_index_) + ")");
  const double dt = (sample.measured_at - e.at).to_seconds();

  // Time update: run the constant-velocity model to the sample's instant.
  const glm::dquat step = quat_from_rotation_vector(e.angular_velocity_rad_s * dt);
  const glm::dquat q_pred = glm::normalize(step * e.pose.orientation);
  const glm::dvec3 p_pred = e.pose.position_m + e.velocity_m_s * dt;
  predict_covariance(orientation_p_, rotation_matrix(step), dt, angular_psd_);
  predict_covariance(position_p_, Matrix3::Identity(), dt, linear_psd_);

  // Measurement update; the orientation innovation is a short-arc rotation vector.
  const Vector6 dq =
      update(orientation_p_, to_eigen(rotation_vector_between(q_pred, sample.pose.orientation)), orientation_r_);
  const Vector6 dp = update(position_p_, to_eigen(sample.pose.position_m - p_pred), position_r_);

  e.at = sample.measured_at;
  e.pose.orientation = glm::normalize(quat_from_rotation_vector(to_glm(dq.head<3>())) * q_pred);
  e.angular_velocity_rad_s += to_glm(dq.tail<3>());
  e.pose.position_m = p_pred + to_glm(dp.head<3>());
  e.velocity_m_s += to_glm(dp.tail<3>());
  last_index_ = sample.index;
}

}  // namespace latsim::tracker
