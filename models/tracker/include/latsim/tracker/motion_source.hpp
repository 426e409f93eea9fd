// Head-motion sources: the true head pose as a function of simulated time.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "latsim/des/time.hpp"
#include "latsim/tracker/pose.hpp"
#include "latsim/tracker/trace.hpp"

namespace latsim::tracker {

/// The ground-truth head pose over time, which trackers sample and registration
/// error is measured against. Implementations are pure functions of time.
class MotionSource {
 public:
  virtual ~MotionSource() = default;
  virtual Pose pose_at(des::Time t) const = 0;
  virtual std::string name() const = 0;
  /// True when the pose never changes (lets pipelines skip motion work).
  virtual bool is_still() const { return false; }
};

/// A head that never moves.
class StillMotion final : public MotionSource {
 public:
  explicit StillMotion(Pose pose) : pose_(pose) {}
  Pose pose_at(des::Time) const override { return pose_; }
  std::string name() const override { return "still"; }
  bool is_still() const override { return true; }

 private:
  Pose pose_;
};

/// A head turning at a constant rate about a fixed world axis through its own
/// position: orientation(t) = exp(rate * t * axis) * start.orientation.
class ConstantAngularVelocity final : public MotionSource {
 public:
  /// `axis` in world coordinates (normalised here; must be non-zero);
  /// positive rates turn counter-clockwise about it (right-hand rule).
  ConstantAngularVelocity(Pose start, glm::dvec3 axis, double rate_deg_s);
  Pose pose_at(des::Time t) const override;
  std::string name() const override { return "constant"; }
  bool is_still() const override { return rate_deg_s_ == 0.0; }

 private:
  Pose start_;
  glm::dvec3 axis_;
  double rate_deg_s_;
};

/// Settings of SinusoidalMotion; angles in degrees, phases at t = 0.
struct SinusoidParams {
  double yaw_amplitude_deg = 0.0;
  double yaw_frequency_hz = 0.0;
  double yaw_phase_deg = 0.0;
  double pitch_amplitude_deg = 0.0;
  double pitch_frequency_hz = 0.0;
  double pitch_phase_deg = 0.0;
  glm::dvec3 position_m{0.0, 0.0, 0.0};
};

/// A head shaking and nodding: yaw(t) = A_y sin(2 pi f_y t + phi_y) and
/// pitch(t) = A_p sin(2 pi f_p t + phi_p), composed as quat_from_yaw_pitch.
class SinusoidalMotion final : public MotionSource {
 public:
  explicit SinusoidalMotion(SinusoidParams params);
  Pose pose_at(des::Time t) const override;
  std::string name() const override { return "sinusoid"; }
  bool is_still() const override;
  /// Yaw and pitch in radians at time t (the angles the pose is built from).
  double yaw_rad_at(des::Time t) const;
  double pitch_rad_at(des::Time t) const;

 private:
  SinusoidParams params_;
};

/// Settings of PolylineWalk.
struct WalkParams {
  std::vector<glm::dvec3> points_m;
  double speed_m_s = 1.0;
  /// Looping walks return from the last point to the first along a closing
  /// segment and go round again; otherwise the walker stops at the ends.
  bool loop = false;
  /// Look horizontally along the direction of travel; otherwise keep `orientation`.
  bool face_direction = true;
  /// Facing the direction: how fast the head turns at a corner (yaw, deg/s;
  /// 0: at once). The turn is centred on the corner, at this constant rate,
  /// unless the legs on either side are shorter than half the turn's walk,
  /// which then shortens (and speeds) it.
  double turn_rate_deg_s = 90.0;
  glm::dquat orientation{1.0, 0.0, 0.0, 0.0};
};

/// A walker moving along a polyline at constant speed: at time t it is at
/// arc length s = speed * t along the path (t < 0 stays at the start).
class PolylineWalk final : public MotionSource {
 public:
  explicit PolylineWalk(WalkParams params);
  Pose pose_at(des::Time t) const override;
  std::string name() const override { return "walk"; }
  bool is_still() const override { return path_length_m_ == 0.0; }
  /// Total length of the path walked per lap (closing segment included when looping).
  double path_length_m() const { return path_length_m_; }
  /// Pose at arc length s along the path (clamped or wrapped as configured).
  Pose pose_at_distance(double s_m) const;

 private:
  struct Segment {
    glm::dvec3 from_m;
    glm::dvec3 to_m;
    double start_s_m;
    double length_m;
    glm::dquat facing;
    double turn_in_m = 0.0;  ///< half-length of the turn at this segment's start (0: none)
  };
  // Orientation at arc length s (in [0, path length]) on segment i.
  glm::dquat facing_at(size_t i, double s) const;

  WalkParams params_;
  std::vector<Segment> segments_;  // only segments of positive length
  double path_length_m_ = 0.0;
};

/// Replays a recorded trace: pose at trace time t + offset, orientation by
/// short-arc slerp and position by linear interpolation between neighbouring
/// samples. Outside the recording it either holds the first/last sample or,
/// looping, wraps around: a lap lasts the recording plus one mean sample
/// interval, across which the last sample is interpolated back to the first,
/// so the wrap is as smooth as the recording itself.
class TraceMotion final : public MotionSource {
 public:
  TraceMotion(std::shared_ptr<const Trace> trace, des::Time offset, bool loop);
  Pose pose_at(des::Time t) const override;
  std::string name() const override { return "trace"; }
  bool is_still() const override { return trace_->samples.size() < 2; }
  const Trace& trace() const { return *trace_; }

 private:
  Pose interpolate(des::Time u) const;

  std::shared_ptr<const Trace> trace_;
  des::Time offset_;
  bool loop_;
  des::Time lap_;  // looping period
};

}  // namespace latsim::tracker
