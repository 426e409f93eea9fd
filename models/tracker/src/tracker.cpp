#include "latsim/tracker/tracker.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>

namespace latsim::tracker {

NoiseCovariance noise_factor(const NoiseCovariance& covariance) {
  if (!covariance.allFinite()) throw std::invalid_argument("noise covariance has non-finite entries");
  const double scale = covariance.cwiseAbs().maxCoeff();
  if (scale == 0.0) return NoiseCovariance::Zero();
  // Tolerances relative to the largest entry: round-off in a hand-written
  // matrix must not make a valid covariance fail.
  const double tolerance = 1e-12 * scale;
  if (((covariance - covariance.transpose()).cwiseAbs().array() > tolerance).any())
    throw std::invalid_argument("noise covariance is not symmetric");

  const Eigen::LLT<NoiseCovariance> llt(covariance);
  if (llt.info() == Eigen::Success) return llt.matrixL();

  const Eigen::LDLT<NoiseCovariance> ldlt(covariance);
  if (ldlt.info() != Eigen::Success) throw std::invalid_argument("noise covariance could not be factorised");
  Eigen::Matrix<double, 6, 1> d = ldlt.vectorD();
  for (int i = 0; i < 6; ++i) {
    if (d(i) < -tolerance)
      throw std::invalid_argument("noise covariance is not positive semidefinite (a pivot of its LDLT is " +
                                  std::to_string(d(i)) + ")");
    d(i) = std::sqrt(std::max(d(i), 0.0));
  }
  // A = P^T L D L^T P, so F = P^T L sqrt(D) satisfies F F^T = A.
  const NoiseCovariance l = ldlt.matrixL();
  NoiseCovariance f = ldlt.transpositionsP().transpose() * (l * d.asDiagonal());
  return f;
}

Tracker::Tracker(TrackerParams params, const MotionSource& motion, des::RandomStream stream)
    : params_(params),
      motion_(motion),
      schedule_(params.clock.phase.value_or(des::Time::zero()),
                des::period_with_rate_error(params.period, params.clock.rate_error_ppm)),
      jitter_stream_(stream.substream("jitter")),
      noise_stream_(stream.substream("noise")),
      loss_stream_(stream.substream("report_loss")),
      noise_factor_(params.noise_enabled ? noise_factor(params.noise_covariance) : NoiseCovariance::Zero()) {
  if (params.internal_delay < des::Time::zero()) throw std::invalid_argument("tracker internal delay is negative");
  if (params.jitter < des::Time::zero()) throw std::invalid_argument("tracker jitter is negative");
  if (params.clock.phase.value_or(des::Time::zero()) < des::Time::zero()) throw std::invalid_argument("tracker phase is negative");
  if (params_.imu) {
    if (params_.imu->samples_per_report < 1) throw std::invalid_argument("an IMU report carries at least one reading");
    if (params_.imu->report_every < 1) throw std::invalid_argument("IMU reports come at least every reading");
    const double p = params_.imu->report_loss_probability;
    if (!(p >= 0.0 && p < 1.0)) throw std::invalid_argument("IMU report loss probability must lie in [0, 1)");
    imu_ = std::make_unique<Imu>(params_.imu->gyro, schedule_, motion_, stream.substream("imu"));
  }
}

TrackerSample Tracker::imu_report(int64_t k) {
  // The readings between the last report asked for and this one are read
  // too (a report carries the newest ones, and readings come in order).
  const int n = params_.imu->samples_per_report;
  // Never before the first report: the chain starts there.
  const int64_t from = readings_.empty() ? (any_sample_ ? k - n + 1 : k) : std::max(k - n + 1, readings_.back().index + 1);
  for (int64_t j = from; j <= k; ++j) readings_.push_back(imu_->read(j));
  while (!readings_.empty() && readings_.front().index <= k - n) readings_.pop_front();
  auto report = std::make_shared<ImuReport>();
  report->readings.assign(readings_.begin(), readings_.end());
  TrackerSample s;
  s.index = k;
  s.measured_at = schedule_.at(k);
  s.ready_at = s.measured_at + params_.internal_delay;
  s.pose = motion_.pose_at(s.measured_at);
  s.imu = std::move(report);
  // Drawn only when reports can be lost.
  if (params_.imu->report_loss_probability > 0.0) s.lost = loss_stream_.bernoulli(params_.imu->report_loss_probability);
  return s;
}

des::Time Tracker::jitter_offset() {
  const int64_t j = params_.jitter.ticks();
  if (j == 0) return des::Time::zero();
  if (params_.jitter_shape == TrackerParams::Uniform) {
    // Exactly uniform over the integer ticks of [-j, +j].
    const auto draw = jitter_stream_.uniform_int(static_cast<uint64_t>(2 * j + 1));
    return des::Time::ps(static_cast<int64_t>(draw) - j);
  }
  return des::Time::from_seconds(jitter_stream_.normal(0.0, params_.jitter.to_seconds()));
}

Pose Tracker::add_noise(const Pose& truth, des::RandomStream& stream) const {
  if (!params_.noise_enabled) return truth;
  Eigen::Matrix<double, 6, 1> z;
  for (int i = 0; i < 6; ++i) z(i) = stream.normal();
  const Eigen::Matrix<double, 6, 1> n = noise_factor_ * z;
  Pose noisy;
  noisy.position_m = truth.position_m + glm::dvec3{n(0), n(1), n(2)};
  noisy.orientation = glm::normalize(quat_from_rotation_vector(glm::dvec3{n(3), n(4), n(5)}) * truth.orientation);
  return noisy;
}

Pose Tracker::measure_object(const MotionSource& object, des::Time at, des::RandomStream& noise) const {
  return add_noise(object.pose_at(at), noise);
}

TrackerSample Tracker::sample(int64_t k) {
  if (any_sample_ && k <= last_index_)
    throw std::logic_error("tracker samples must be requested in increasing index order (asked for " +
                           std::to_string(k) + " after " + std::to_string(last_index_) + ")");
  if (imu_) {
    TrackerSample s = imu_report(k);
    any_sample_ = true;
    last_index_ = k;
    last_measured_at_ = s.measured_at;
    return s;
  }
  des::Time measured = schedule_.at(k) + jitter_offset();
  // Clamping keeps reports in order even when jitter exceeds half a period.
  const des::Time earliest = any_sample_ ? last_measured_at_ + des::Time::ps(1) : des::Time::zero();
  measured = std::max(measured, earliest);

  TrackerSample s;
  s.index = k;
  s.measured_at = measured;
  s.ready_at = measured + params_.internal_delay;
  s.pose = add_noise(motion_.pose_at(measured), noise_stream_);

  any_sample_ = true;
  last_index_ = k;
  last_measured_at_ = measured;
  return s;
}

}  // namespace latsim::tracker
