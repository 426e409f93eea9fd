// A head tracker: periodic, jittered, delayed, noisy samples of a motion source.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>

#include <Eigen/Core>

#include "latsim/des/clock.hpp"
#include "latsim/des/random.hpp"
#include "latsim/des/time.hpp"
#include "latsim/tracker/imu_chain.hpp"
#include "latsim/tracker/motion_source.hpp"
#include "latsim/tracker/pose.hpp"

namespace latsim::tracker {

/// 6x6 covariance of pose noise; order x, y, z (m^2), then the rotation
/// vector rx, ry, rz (rad^2), rotation in world axes.
using NoiseCovariance = Eigen::Matrix<double, 6, 6>;

/// How a tracker samples: rate, processing delay, timing jitter and noise.
struct TrackerParams {
  enum JitterShape { Uniform, Normal };

  /// Exact nominal sampling period (e.g. RationalSeconds::period_of_hz(60000, 1001)).
  des::RationalSeconds period{1, 60};
  /// From measuring the pose to the record starting to leave the tracker.
  des::Time internal_delay;
  /// Uniform: offsets uniform on [-jitter, +jitter]; Normal: standard deviation.
  des::Time jitter;
  JitterShape jitter_shape = Uniform;
  NoiseCovariance noise_covariance = NoiseCovariance::Zero();
  bool noise_enabled = false;
  /// The tracker's oscillator: time of sample 0 (none: 0; a run draws one)
  /// and rate error (the actual period is `period` corrected by it).
  des::ClockSettings clock;
  /// An IMU tracking chain (/tracker/imu): samples are gyro readings at the
  /// tracker's rate, carried in reports and fused by the runtime, instead of
  /// measured poses; jitter and pose noise are not used.
  std::optional<ImuChainParams> imu;
};

/// One tracker report.
struct TrackerSample {
  int64_t index = 0;
  /// When the pose was sampled (the start of motion-to-photon latency).
  des::Time measured_at;
  /// measured_at + internal delay: the record starts leaving the tracker.
  des::Time ready_at;
  /// The measured pose, noise included. From an IMU chain: the true pose
  /// until the runtime fuses the report, then the fused one.
  Pose pose;
  /// An IMU chain's report: the readings it carries; null otherwise.
  std::shared_ptr<const ImuReport> imu;
  /// The report never reaches the host (an IMU chain's lost report).
  bool lost = false;
  /// After the runtime's fusion: the angular velocity (world frame) and
  /// velocity it believes; absent for measured poses.
  std::optional<glm::dvec3> angular_velocity_rad_s;
  glm::dvec3 velocity_m_s{0.0};
};

/// A factor F with F F^T = covariance: the Cholesky factor (Eigen LLT) when
/// the matrix is positive definite, else P^T L sqrt(D) from a pivoted LDLT so
/// semidefinite matrices (e.g. position-only noise) work too. Throws
/// std::invalid_argument naming the problem when the matrix is not
/// symmetric, not finite or not positive semidefinite.
NoiseCovariance noise_factor(const NoiseCovariance& covariance);

/// Produces samples k = 0, 1, 2, ... of a motion source. Sample k is nominally
/// measured at phase + k * period (exact, from the index; the period with
/// the clock's rate error applied); jitter adds a
/// random offset and noise perturbs the pose. Jitter and noise draw from two
/// substreams ("jitter", "noise") of the tracker's stream, so switching one on
/// does not change the other's numbers; with neither configured nothing is
/// drawn. Samples must be requested in increasing k (each sample's jitter is
/// clamped against the previous one's, keeping measurement times strictly
/// increasing and never before time zero); indices may be skipped. The
/// motion source must outlive the tracker.
class Tracker {
 public:
  Tracker(TrackerParams params, const MotionSource& motion, des::RandomStream stream);

  /// Sample k; throws std::logic_error if k is not greater than the last k.
  TrackerSample sample(int64_t k);
  /// Another tracked object (a handheld controller) measured at the instant
  /// of a head sample, with the tracker's noise drawn from `noise` (a stream
  /// of the object's own, so that tracking it changes no head sample).
  Pose measure_object(const MotionSource& object, des::Time at, des::RandomStream& noise) const;
  /// The sample after sample k: k + 1, or an IMU chain's next report.
  int64_t next_index(int64_t k) const { return k + (params_.imu ? params_.imu->report_every : 1); }
  /// Time of sample k without jitter.
  des::Time nominal_time(int64_t k) const { return schedule_.at(k); }
  /// Index of the first sample nominally at or after t.
  int64_t first_index_at_or_after(des::Time t) const { return schedule_.index_at_or_after(t); }
  const TrackerParams& params() const { return params_; }
  const MotionSource& motion() const { return motion_; }

 private:
  des::Time jitter_offset();
  Pose add_noise(const Pose& truth, des::RandomStream& stream) const;
  TrackerSample imu_report(int64_t k);

  TrackerParams params_;
  const MotionSource& motion_;
  des::PeriodicSchedule schedule_;
  des::RandomStream jitter_stream_;
  des::RandomStream noise_stream_;
  des::RandomStream loss_stream_;
  std::unique_ptr<Imu> imu_;
  std::deque<ImuReading> readings_;  ///< the newest readings (IMU chain)
  NoiseCovariance noise_factor_;
  int64_t last_index_ = 0;
  des::Time last_measured_at_;
  bool any_sample_ = false;
};

}  // namespace latsim::tracker
