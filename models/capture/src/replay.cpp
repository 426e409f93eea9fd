#include "latsim/capture/replay.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace latsim::capture {

Replay::Replay(std::shared_ptr<const std::vector<des::Time>> values, const ReplayParams& params)
    : values_(std::move(values)), params_(params) {
  if (!values_ || values_->empty()) throw std::invalid_argument("a capture column without values");
  if (!(params_.scale >= 0.0 && std::isfinite(params_.scale))) throw std::invalid_argument("scale must be at least 0");
  const auto n = static_cast<int64_t>(values_->size());
  if (params_.order == ReplayParams::Order::bootstrap && (params_.block_length < 1 || params_.block_length > n))
    throw std::invalid_argument("block_length " + std::to_string(params_.block_length) + " is not within 1 and the " +
                                std::to_string(n) + " values of the column");
  if (params_.max_ms) max_ = des::Time::from_ms(*params_.max_ms);
  __int128 sum = 0;
  for (des::Time v : *values_) {
    const des::Time t = scaled(v);
    if (t < des::Time::zero())
      throw std::invalid_argument("a value of " + std::to_string(v.to_ms()) + " ms becomes " +
                                  std::to_string(t.to_ms()) + " ms with this scale and offset: a duration below zero");
    if (max_ && t > *max_) ++clipped_;
    sum += transformed(v).ticks();
  }
  mean_ = des::Time::ps(static_cast<int64_t>((sum + n / 2) / n));
}

des::Time Replay::scaled(des::Time v) const {
  des::Time t = v;
  if (params_.scale != 1.0) {
    const double ps = std::round(static_cast<double>(v.ticks()) * params_.scale);
    if (!(std::fabs(ps) < 9.0e18)) throw std::invalid_argument("scale takes a value past the range of time");
    t = des::Time::ps(static_cast<int64_t>(ps));
  }
  if (params_.offset_ms != 0.0) t = t + des::Time::from_ms(params_.offset_ms);
  return t;
}

des::Time Replay::transformed(des::Time v) const {
  const des::Time t = scaled(v);
  return max_ && t > *max_ ? *max_ : t;
}

des::Time Replay::next(des::RandomStream& stream) {
  const std::vector<des::Time>& v = *values_;
  if (params_.order == ReplayParams::Order::bootstrap) {
    if (block_left_ == 0) {
      next_ = static_cast<size_t>(stream.uniform_int(v.size()));
      block_left_ = params_.block_length;
    }
    --block_left_;
  } else if (next_ == v.size()) {
    if (params_.at_end == ReplayParams::AtEnd::stop) {
      exhausted_ = true;
      return transformed(v.back());
    }
    next_ = 0;
    ++wraps_;
  }
  const des::Time t = transformed(v[next_]);
  ++next_;
  if (params_.order == ReplayParams::Order::bootstrap && next_ == v.size()) next_ = 0;  // circular blocks
  if (params_.order == ReplayParams::Order::in_order && params_.at_end == ReplayParams::AtEnd::stop &&
      next_ == v.size())
    exhausted_ = true;
  ++played_;
  return t;
}

}  // namespace latsim::capture
