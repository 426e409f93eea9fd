// The fusion a headset's runtime runs: the gyroscope integrated into an
// orientation, pulled towards each absolute reference fix, with the gyro's
// bias estimated from what the fixes correct.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>

#include <glm/vec3.hpp>

#include "latsim/des/time.hpp"
#include "latsim/tracker/imu.hpp"
#include "latsim/tracker/optical_reference.hpp"
#include "latsim/tracker/pose.hpp"

namespace latsim::tracker {

/// Gains of the complementary filter, as time constants.
struct FusionParams {
  /// Each fix pulls the orientation by 1 - exp(-dt / tau) of the error it
  /// measures, dt the time since the previous fix.
  des::Time orientation_time_constant = des::Time::ms(500);
  /// The bias estimate follows the rate error each fix implies (its error
  /// over the time since the previous fix) with this time constant: each fix
  /// moves it by error / tau (0: no bias estimate).
  des::Time bias_time_constant = des::Time::s(10);
  /// true: a fix is compared with the orientation the filter had at the
  /// fix's measurement instant (kept for `history` of readings); false: with
  /// its newest orientation, so that a delayed fix drags a turning estimate back.
  bool align_reference = true;
  des::Time history = des::Time::ms(200);
  /// The angular velocity reported: the mean of the newest n bias-corrected readings.
  int rate_readings = 1;
};

/// A complementary filter on orientation (gyro path high, reference path
/// low) with integral bias correction, fed the gyro readings in index order
/// and the fixes in measurement order. Readings skipped (lost reports) are
/// covered by the next reading's rate over the whole gap, as a runtime that
/// only has that reading must.
class ComplementaryFilter {
 public:
  explicit ComplementaryFilter(FusionParams params);

  /// Starts at `pose` at device time `stamp` (the first reading's is used when not started).
  void start(const Pose& pose, des::Time stamp);
  bool started() const { return started_; }
  /// Integrates a reading newer than the last one.
  void integrate(const ImuReading& r);
  /// Corrects with a fix measured no later than the newest reading; false
  /// when it is newer (the caller keeps it for later) or older than the history.
  bool correct(const ReferenceFix& f);

  des::Time stamp() const { return stamp_; }
  const glm::dquat& orientation() const { return orientation_; }
  /// The world-frame angular velocity the runtime believes (bias removed).
  glm::dvec3 angular_velocity_rad_s() const;
  const glm::dvec3& bias_rad_s() const { return bias_rad_s_; }
  /// Position dead-reckoned from the last fixes to stamp(), and their velocity.
  glm::dvec3 position_m() const;
  const glm::dvec3& velocity_m_s() const { return velocity_m_s_; }
  int64_t last_index() const { return last_index_; }

 private:
  struct Past {
    des::Time stamp;
    glm::dquat orientation;
  };
  glm::dquat orientation_at(des::Time t) const;

  FusionParams params_;
  bool started_ = false;
  des::Time stamp_;
  glm::dquat orientation_{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 bias_rad_s_{0.0};
  std::deque<glm::dvec3> rates_;  ///< newest readings, bias not removed
  std::deque<Past> history_;
  int64_t last_index_ = -1;
  std::optional<des::Time> last_fix_at_;
  des::Time fix_at_;
  glm::dvec3 fix_position_m_{0.0};
  glm::dvec3 velocity_m_s_{0.0};
};

}  // namespace latsim::tracker
