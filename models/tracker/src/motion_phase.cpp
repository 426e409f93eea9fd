#include "latsim/tracker/motion_phase.hpp"
#include "latsim/des/stop_token.hpp"
#include "latsim/units/units.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace latsim::tracker {

std::string_view phase_name(MotionPhase phase) {
  switch (phase) {
    case MotionPhase::Still: return "still";
    case MotionPhase::Onset: return "onset";
    case MotionPhase::Steady: return "steady";
    case MotionPhase::Stop: return "stop";
  }
  return "still";
}

MotionPhaseClassifier::MotionPhaseClassifier(const MotionSource& motion, MotionPhaseParams params)
    : motion_(motion),
      params_(params),
      threshold_rad_s_(units::deg_to_rad(params.threshold_deg_s)),
      rest_rad_s_(units::deg_to_rad(params.rest_deg_s)) {
  if (!std::isfinite(params.threshold_deg_s) || params.threshold_deg_s < 0.0)
    throw std::invalid_argument("motion phase threshold must be finite and not negative");
  if (params.window <= des::Time::zero()) throw std::invalid_argument("motion phase window must be positive");
  if (params.step <= des::Time::zero()) throw std::invalid_argument("motion phase step must be positive");
  if (!std::isfinite(params.rest_deg_s) || params.rest_deg_s < 0.0)
    throw std::invalid_argument("motion phase rest speed must be finite and not negative");
}

double MotionPhaseClassifier::speed_of_next_interval() {
  // Interval evaluated_ + 1 starts where the previous one ended.
  const glm::dquat from = grid_end_;
  grid_end_ = motion_.pose_at(params_.step * (evaluated_ + 2)).orientation;
  ++evaluated_;
  return angle_between(from, grid_end_) / params_.step.to_seconds();
}

void MotionPhaseClassifier::extend_to(int64_t k) {
  if (evaluated_ < 0) {
    grid_end_ = motion_.pose_at(des::Time::zero()).orientation;
    const double speed = speed_of_next_interval();
    initial_moving_ = last_moving_ = speed > threshold_rad_s_;
    if (speed <= rest_rad_s_) {
      rest_run_start_ = des::Time::zero();
      last_rest_end_ = params_.step;
    }
  }
  uint64_t steps = 0;
  while (evaluated_ < k) {
    // An instant far past the run (a photon a long response later) costs a
    // step per grid interval: a stop request must not wait for them all.
    des::check_stop_every(steps, 4096);
    const double speed = speed_of_next_interval();
    const bool moving = speed > threshold_rad_s_;
    if (moving != last_moving_) {
      des::Time at = params_.step * evaluated_;
      // A start from rest (at least a window of it) is dated where the head
      // left rest; a head that only turns round is not at rest.
      const des::Time previous = transitions_.empty() ? des::Time::zero() : transitions_.back().at;
      const bool rested = last_rest_end_ - rest_run_start_ >= params_.window;
      if (moving && rested && last_rest_end_ >= previous && last_rest_end_ < at) at = last_rest_end_;
      transitions_.push_back(Transition{at, moving});
    }
    if (speed <= rest_rad_s_) {
      if (last_rest_end_ != params_.step * evaluated_) rest_run_start_ = params_.step * evaluated_;
      last_rest_end_ = params_.step * (evaluated_ + 1);
    }
    last_moving_ = moving;
  }
}

std::vector<des::Time> MotionPhaseClassifier::starts_until(des::Time t) {
  if (t < des::Time::zero()) return {};
  extend_to((t + params_.window) / params_.step);
  std::vector<des::Time> starts;
  for (const Transition& tr : transitions_)
    if (tr.moving && tr.at <= t) starts.push_back(tr.at);
  return starts;
}

MotionPhase MotionPhaseClassifier::phase_at(des::Time t) {
  if (t < des::Time::zero()) t = des::Time::zero();
  // A start is dated back to where the head left rest: look a window ahead
  // so that a movement crossing the threshold after t but starting before it is known.
  extend_to((t + params_.window) / params_.step);
  // The newest transition at or before t decides the state.
  const auto after = std::upper_bound(transitions_.begin(), transitions_.end(), t,
                                      [](des::Time v, const Transition& tr) { return v < tr.at; });
  if (after == transitions_.begin()) return initial_moving_ ? MotionPhase::Steady : MotionPhase::Still;
  const Transition& last = *std::prev(after);
  const bool recent = t - last.at < params_.window;
  if (last.moving) return recent ? MotionPhase::Onset : MotionPhase::Steady;
  return recent ? MotionPhase::Stop : MotionPhase::Still;
}

}  // namespace latsim::tracker
