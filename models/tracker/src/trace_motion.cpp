#include <algorithm>
#include <stdexcept>

#include "latsim/tracker/motion_source.hpp"

namespace latsim::tracker {

namespace {

Pose blend(const Pose& a, const Pose& b, double f) {
  return Pose{a.position_m + (b.position_m - a.position_m) * f, slerp_short(a.orientation, b.orientation, f)};
}

double fraction(des::Time from, des::Time to, des::Time at) {
  return static_cast<double>((at - from).ticks()) / static_cast<double>((to - from).ticks());
}

}  // namespace

TraceMotion::TraceMotion(std::shared_ptr<const Trace> trace, des::Time offset, bool loop)
    : trace_(std::move(trace)), offset_(offset), loop_(loop) {
  if (!trace_ || trace_->samples.empty()) throw std::invalid_argument("trace motion needs a non-empty trace");
  const auto n = static_cast<int64_t>(trace_->samples.size());
  const des::Time span = trace_->end() - trace_->start();
  lap_ = n < 2 ? des::Time::zero() : span + des::Time::ps(span.ticks() / (n - 1));
}

Pose TraceMotion::pose_at(des::Time t) const {
  const auto& samples = trace_->samples;
  const des::Time u = t + offset_;
  if (samples.size() < 2) return samples.front().pose;
  if (!loop_) return interpolate(std::clamp(u, trace_->start(), trace_->end()));

  // Position within the lap, computed from integer ticks so no drift builds up.
  des::Time into_lap = (u - trace_->start()) % lap_;
  if (into_lap < des::Time::zero()) into_lap += lap_;
  const des::Time w = trace_->start() + into_lap;
  if (w <= trace_->end()) return interpolate(w);
  // The closing gap from the last sample back round to the first.
  return blend(samples.back().pose, samples.front().pose, fraction(trace_->end(), trace_->start() + lap_, w));
}

Pose TraceMotion::interpolate(des::Time u) const {
  const auto& samples = trace_->samples;
  const auto after = std::upper_bound(samples.begin(), samples.end(), u,
                                      [](des::Time v, const TraceSample& s) { return v < s.t; });
  if (after == samples.begin()) return samples.front().pose;
  if (after == samples.end()) return samples.back().pose;
  const TraceSample& a = *std::prev(after);
  return blend(a.pose, after->pose, fraction(a.t, after->t, u));
}

}  // namespace latsim::tracker
