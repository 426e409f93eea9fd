// Classifying instants of a head motion into still, onset, steady and stop.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "latsim/des/time.hpp"
#include "latsim/tracker/motion_source.hpp"

namespace latsim::tracker {

/// The part of a movement an instant belongs to.
enum class MotionPhase { Still, Onset, Steady, Stop };

/// "still", "onset", "steady", "stop": the suffixes of split figures.
std::string_view phase_name(MotionPhase phase);

/// Settings of MotionPhaseClassifier.
struct MotionPhaseParams {
  /// The head is moving while its angular speed exceeds this. The default
  /// lies above the slow drift of a person watching (the bundled recording
  /// moves at about 24 deg/s typically) and below deliberate head turns.
  double threshold_deg_s = 40.0;
  /// How long after the head starts (stops) moving an instant counts as
  /// onset (stop): about what a predictor needs to see a new velocity (one
  /// or two samples) plus a typical motion-to-photon latency.
  des::Time window = des::Time::ms(100);
  /// The grid on which the angular speed is measured: the mean speed over
  /// each interval [k step, (k + 1) step).
  des::Time step = des::Time::ms(5);
  /// A movement starts where the head leaves rest, not where it passes the
  /// threshold: a start is moved back to the end of the last interval whose
  /// speed was at most this (at rest, for at least `window` in a row) since
  /// the previous stop, when there is one (a movement out of slow drift, or a
  /// head that only turns round, keeps the threshold crossing).
  double rest_deg_s = 0.5;
};

/// Tells, from the true head motion, whether an instant lies within `window`
/// after the head started moving (onset) or stopped (stop), or otherwise in
/// steady motion or at rest. The angular speed of grid interval k is the
/// rotation angle between the poses at its ends over its length; a movement
/// is a rise of that speed above the threshold from one interval to the
/// next, and it starts where the head left rest (the end of the last
/// interval at or below rest_deg_s, after at least `window` of them, since
/// the previous stop; the threshold crossing itself when there is none); the
/// head stops where the speed falls to or below the threshold. A movement whose speed takes longer than
/// `window` from leaving rest to the threshold is dated at most a window back
/// from any instant asked about (the grid is evaluated a window ahead). Its state
/// at time zero is not a transition. The grid is evaluated lazily as later
/// instants are asked for; only the transitions are kept, so memory grows
/// with the number of starts and stops, not with time.
class MotionPhaseClassifier {
 public:
  /// Throws std::invalid_argument for a negative or non-finite threshold or a
  /// non-positive window or step. The motion source must outlive the classifier.
  MotionPhaseClassifier(const MotionSource& motion, MotionPhaseParams params);

  /// The phase at t >= 0 (earlier times count as time zero).
  MotionPhase phase_at(des::Time t);
  /// Instants at or before t at which the head started moving (the grid is
  /// evaluated that far).
  std::vector<des::Time> starts_until(des::Time t);
  /// Starts and stops found so far.
  int64_t transitions() const { return static_cast<int64_t>(transitions_.size()); }
  const MotionPhaseParams& params() const { return params_; }

 private:
  /// The angular speed (rad/s) of grid interval evaluated_ + 1; advances to it.
  double speed_of_next_interval();
  void extend_to(int64_t k);

  struct Transition {
    des::Time at;
    bool moving;  ///< the state it starts
  };
  const MotionSource& motion_;
  MotionPhaseParams params_;
  double threshold_rad_s_;
  double rest_rad_s_;
  des::Time last_rest_end_ = des::Time::ps(-1);  ///< end of the newest interval at rest
  des::Time rest_run_start_ = des::Time::ps(-1); ///< start of the run of intervals at rest it ends
  bool initial_moving_ = false;
  int64_t evaluated_ = -1;  ///< last grid interval classified
  glm::dquat grid_end_{1.0, 0.0, 0.0, 0.0};  ///< orientation at the end of interval evaluated_
  bool last_moving_ = false;
  std::vector<Transition> transitions_;
};

}  // namespace latsim::tracker
