// Bindings of /host/prediction and /motion_phases.
#include <cmath>
#include <optional>

#include "latsim/sections/shared.hpp"
#include "latsim/units/units.hpp"

namespace latsim::sections {

using scenario::KeySpec;
using scenario::Section;

namespace {


/// Keys of the Kalman filter; its measurement noise defaults to the tracker's.
void kalman(Section& s, tracker::KalmanParams& k, const tracker::TrackerParams& tracker) {
  s.number("angular_accel_noise_deg_s2_rthz", k.angular_accel_noise_deg_s2_rthz,
           {.unit = "deg/s²/√Hz", .min = 0.0, .above_min = true,
            .doc = "process noise: spectral density of the head's angular acceleration (more: less lag, less "
                   "smoothing)"});
  s.number("linear_accel_noise_m_s2_rthz", k.linear_accel_noise_m_s2_rthz,
           {.unit = "m/s²/√Hz", .min = 0.0, .above_min = true,
            .doc = "process noise: spectral density of the head's linear acceleration"});
  std::optional<double> orientation_deg, position_m;
  s.number("orientation_stddev_deg", orientation_deg,
           {.unit = "deg", .min = 0.0,
            .doc = "measurement noise of orientation, per axis",
            .default_doc = "the tracker's orientation noise (/tracker/noise)"});
  s.number("position_stddev_m", position_m,
           {.unit = "m", .min = 0.0,
            .doc = "measurement noise of position, per axis",
            .default_doc = "the tracker's position noise (/tracker/noise)"});
  s.number("initial_angular_speed_deg_s", k.initial_angular_speed_deg_s,
           {.unit = "deg/s", .min = 0.0, .above_min = true, .doc = "prior standard deviation of the angular velocity"});
  s.number("initial_speed_m_s", k.initial_speed_m_s,
           {.unit = "m/s", .min = 0.0, .above_min = true, .doc = "prior standard deviation of the velocity"});
  // Tuned to the scenario's tracker: the filter assumes the noise the tracker adds.
  tracker::NoiseCovariance r = tracker.noise_enabled ? tracker.noise_covariance : tracker::NoiseCovariance::Zero();
  if (orientation_deg) {
    r.bottomRows<3>().setZero();
    r.rightCols<3>().setZero();
    for (int i = 3; i < 6; ++i) r(i, i) = std::pow(*orientation_deg * units::kRadPerDeg, 2);
  }
  if (position_m) {
    r.topRows<3>().setZero();
    r.leftCols<3>().setZero();
    for (int i = 0; i < 3; ++i) r(i, i) = *position_m * *position_m;
    if (orientation_deg)
      for (int i = 3; i < 6; ++i) r(i, i) = std::pow(*orientation_deg * units::kRadPerDeg, 2);
    else if (tracker.noise_enabled)
      r.bottomRightCorner<3, 3>() = tracker.noise_covariance.bottomRightCorner<3, 3>();
  }
  k.measurement_covariance = r;
}

}  // namespace

void bind(Section& s, tracker::PredictionParams& p, const tracker::TrackerParams& tracker) {
  s.doc(
      "Pose prediction: the host extrapolates the head pose from its newest sample to the instant the image "
      "computed from it is expected to be lit (the pipeline's own expected photon time: per line or pixel where "
      "the pipeline works per line or pixel, per image otherwise), or by a fixed horizon. Adds the figures "
      "`prediction_error_deg`, `prediction_error_mm` and `prediction_horizon_ms` (docs/prediction.md).");
  using Kind = tracker::PredictorKind;
  s.modes("type", "",
          {{"none", "no prediction: every image shows its sample's pose (the prediction figures then measure the "
                    "error of not predicting)",
            [&p](Section&) { p.predictor.kind = Kind::None; }},
           {"constant_velocity", "extrapolate at the angular and linear velocity of the two newest samples",
            [&p](Section&) { p.predictor.kind = Kind::ConstantVelocity; }},
           {"constant_acceleration", "extrapolate with the velocity and acceleration of the three newest samples",
            [&p](Section&) { p.predictor.kind = Kind::ConstantAcceleration; }},
           {"kalman", "a Kalman filter on orientation and angular velocity, and on position and velocity",
            [&p, &tracker](Section& k) {
              p.predictor.kind = Kind::Kalman;
              kalman(k, p.predictor.kalman, tracker);
            }},
           {"fusion",
            "the runtime's own state: the fused orientation and position of /tracker/imu, carried forward at the "
            "fusion's angular velocity (its newest bias-corrected gyro rate) and velocity",
            [&p, &tracker](Section& f) {
              p.predictor.kind = Kind::Fusion;
              f.check("type", tracker.imu.has_value(), "fusion prediction needs an IMU tracking chain (/tracker/imu)");
            }}},
          {.doc = "which predictor"});
  std::optional<double> horizon_ms;
  s.number("horizon_ms", horizon_ms,
           {.unit = "ms", .min = 0.0, .max = 10000.0,
            .doc = "a fixed horizon past each sample's measurement",
            .default_doc = "the pipeline's expected photon time"});
  if (horizon_ms) p.fixed_horizon = des::Time::from_ms(*horizon_ms);
  s.choice("knowledge", p.knowledge,
           {{"oracle", tracker::PredictionKnowledge::oracle}, {"runtime", tracker::PredictionKnowledge::runtime}},
           {.doc = "what the predictor knows of each sample's measurement time: `oracle`, the true instant; "
                   "`runtime`, only the host's own clock (when the record became visible, less the tracker's "
                   "internal delay and the record's time on the link), so that poll waits, queueing and "
                   "interrupt handlers distort its rates and horizon (docs/prediction.md)"});
}

void bind(Section& s, tracker::MotionPhaseParams& p) {
  s.doc(
      "Splits `registration_error_arcmin` and `prediction_error_deg` by motion phase into `<name>_onset`, "
      "`_stop`, `_steady` and `_still`: an instant is in onset (stop) within `window_ms` after the true head "
      "started (stopped) moving, otherwise steady (moving) or still. A movement is the true head's angular "
      "speed, measured over successive `step_ms` intervals, rising above `threshold_deg_s`; it starts where the "
      "head left rest (`rest_deg_s`), and stops where the speed falls back to the threshold.");
  s.number("threshold_deg_s", p.threshold_deg_s,
           {.unit = "deg/s", .min = 0.0, .max = 1e6, .doc = "angular speed above which the head is moving"});
  s.duration("window_ms", p.window,
             {.unit = "ms", .min = 0.0, .max = 1e6, .above_min = true, .doc = "how long onset and stop last"});
  s.duration("step_ms", p.step,
             {.unit = "ms", .min = 0.0, .max = 1e6, .above_min = true,
              .doc = "interval over which angular speed is measured"});
  s.number("rest_deg_s", p.rest_deg_s,
           {.unit = "deg/s", .min = 0.0, .max = 1e6,
            .doc = "at or below this the head is at rest: a movement that starts from rest (at least window_ms of "
                   "it) starts where the head left it (the end of the last interval at rest), not where it passes "
                   "threshold_deg_s"});
}

}  // namespace latsim::sections
