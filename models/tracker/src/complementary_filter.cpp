#include "latsim/tracker/complementary_filter.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace latsim::tracker {

ComplementaryFilter::ComplementaryFilter(FusionParams params) : params_(params) {
  if (params_.orientation_time_constant <= des::Time::zero())
    throw std::invalid_argument("fusion orientation time constant must be positive");
  if (params_.bias_time_constant < des::Time::zero()) throw std::invalid_argument("fusion bias time constant is negative");
  if (params_.rate_readings < 1) throw std::invalid_argument("fusion rate readings must be at least 1");
}

void ComplementaryFilter::start(const Pose& pose, des::Time stamp) {
  started_ = true;
  stamp_ = stamp;
  orientation_ = pose.orientation;
  fix_at_ = stamp;
  fix_position_m_ = pose.position_m;
  history_.assign(1, Past{stamp, orientation_});
}

void ComplementaryFilter::integrate(const ImuReading& r) {
  if (!started_) throw std::logic_error("complementary filter: integrate before start");
  if (r.index <= last_index_ || r.stamp < stamp_)
    throw std::logic_error("complementary filter: readings must come in increasing order");
  rates_.push_back(r.rate_rad_s);
  while (static_cast<int>(rates_.size()) > params_.rate_readings) rates_.pop_front();
  // Body-frame increment over the time since the last integrated reading.
  const double dt = (r.stamp - stamp_).to_seconds();
  orientation_ = glm::normalize(orientation_ * quat_from_rotation_vector((r.rate_rad_s - bias_rad_s_) * dt));
  stamp_ = r.stamp;
  last_index_ = r.index;
  history_.push_back(Past{stamp_, orientation_});
  while (history_.size() > 2 && history_[1].stamp < stamp_ - params_.history) history_.pop_front();
}

glm::dquat ComplementaryFilter::orientation_at(des::Time t) const {
  auto after = std::lower_bound(history_.begin(), history_.end(), t,
                                [](const Past& p, des::Time v) { return p.stamp < v; });
  if (after == history_.end()) return history_.back().orientation;
  if (after == history_.begin() || after->stamp == t) return after->orientation;
  const Past& before = *std::prev(after);
  const double u = static_cast<double>((t - before.stamp).ticks()) / static_cast<double>((after->stamp - before.stamp).ticks());
  return slerp_short(before.orientation, after->orientation, u);
}

bool ComplementaryFilter::correct(const ReferenceFix& f) {
  if (!started_ || f.measured_at > stamp_) return false;
  if (params_.align_reference && f.measured_at < history_.front().stamp) return false;
  const glm::dquat then = params_.align_reference ? orientation_at(f.measured_at) : orientation_;
  // World-frame error from the estimate to the fix: fix = exp(e) then.
  const glm::dvec3 error = rotation_vector_between(then, f.pose.orientation);
  const des::Time since = last_fix_at_ ? f.measured_at - *last_fix_at_ : des::Time::zero();
  const double dt = std::max(since.to_seconds(), 0.0);
  const double gain = last_fix_at_ ? 1.0 - std::exp(-dt / params_.orientation_time_constant.to_seconds()) : 1.0;
  const glm::dquat pull = quat_from_rotation_vector(error * gain);
  orientation_ = glm::normalize(pull * orientation_);
  for (Past& p : history_) p.orientation = glm::normalize(pull * p.orientation);
  if (params_.bias_time_constant > des::Time::zero() && last_fix_at_) {
    // The orientation drifted by -error over dt: a rate error of -error / dt
    // in world axes, removed over the bias time constant.
    const glm::dvec3 body_error = glm::inverse(orientation_) * error;
    bias_rad_s_ -= body_error / params_.bias_time_constant.to_seconds();
  }
  if (last_fix_at_ && f.measured_at > *last_fix_at_)
    velocity_m_s_ = (f.pose.position_m - fix_position_m_) / dt;
  fix_position_m_ = f.pose.position_m;
  fix_at_ = f.measured_at;
  last_fix_at_ = f.measured_at;
  return true;
}

glm::dvec3 ComplementaryFilter::angular_velocity_rad_s() const {
  if (rates_.empty()) return glm::dvec3(0.0);
  glm::dvec3 mean(0.0);
  for (const glm::dvec3& r : rates_) mean += r;
  mean /= static_cast<double>(rates_.size());
  return orientation_ * (mean - bias_rad_s_);
}

glm::dvec3 ComplementaryFilter::position_m() const {
  return fix_position_m_ + velocity_m_s_ * (stamp_ - fix_at_).to_seconds();
}

}  // namespace latsim::tracker
