#include "frame_stages/pacing_jit.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace latsim::pipelines::frame_stages {

void RecentSpans::add(des::Time span) {
  spans_.push_back(span);
  if (static_cast<int>(spans_.size()) > capacity_) spans_.pop_front();
}

des::Time RecentSpans::percentile(double percent) const {
  std::vector<des::Time> sorted(spans_.begin(), spans_.end());
  std::sort(sorted.begin(), sorted.end());
  const double n = static_cast<double>(sorted.size());
  const auto rank = static_cast<int64_t>(std::ceil(percent / 100.0 * n));
  const int64_t index = std::clamp<int64_t>(rank - 1, 0, static_cast<int64_t>(sorted.size()) - 1);
  return sorted[static_cast<size_t>(index)];
}

namespace {

/// Until a frame has been measured: a whole refresh, the frame woken at the previous retrace.
des::Time estimate_or_period(const RecentSpans& spans, double percent, const PacingClock& clock) {
  return spans.empty() ? clock.period : spans.percentile(percent);
}

/// Phase Sync / Reflex as described: finish right before the latch.
class JustInTimePacer final : public AppPacer {
 public:
  explicit JustInTimePacer(const JustInTimeParams& p) : p_(p), spans_(p.window) {}

  FramePlan plan(des::Time now, const PacingClock& clock) override {
    const des::Time app = estimate_or_period(spans_, p_.percentile, clock);
    const FramePlan plan = plan_for(now, app, p_.margin, clock.period_multiple, last_display_, clock);
    last_display_ = plan.display;
    return plan;
  }
  void measured(const FrameSample& s) override { spans_.add(s.gpu_done - s.woke); }

 private:
  JustInTimeParams p_;
  RecentSpans spans_;
  des::Time last_display_ = des::Time::ps(-1);
};

/// A margin that rises by `raise` at each missed latch and falls by `lower`
/// per frame on time while one more miss in the last `window_s` would keep within the target rate.
class MissRatePacer final : public AppPacer {
 public:
  explicit MissRatePacer(const MissRateParams& p) : p_(p), spans_(p.median_window), margin_(p.initial_margin) {}

  FramePlan plan(des::Time now, const PacingClock& clock) override {
    period_ = clock.period;
    const des::Time app = estimate_or_period(spans_, 50.0, clock);
    const FramePlan plan = plan_for(now, app, margin_, clock.period_multiple, last_display_, clock);
    last_display_ = plan.display;
    return plan;
  }

  void measured(const FrameSample& s) override {
    spans_.add(s.gpu_done - s.woke);
    const des::Time window = des::Time::from_seconds(p_.window_s);
    while (!misses_.empty() && misses_.front() <= s.gpu_done - window) misses_.pop_front();
    if (s.missed) {
      misses_.push_back(s.gpu_done);
      margin_ = std::min(margin_ + p_.raise, period_);
      return;
    }
    // Lower only while one more miss would still keep the window at or below the target rate.
    const double per_min_after_one_more = static_cast<double>(misses_.size() + 1) * 60.0 / p_.window_s;
    if (per_min_after_one_more <= p_.target_per_min) margin_ = std::max(des::Time::zero(), margin_ - p_.lower);
  }

 private:
  MissRateParams p_;
  RecentSpans spans_;
  des::Time margin_;
  des::Time period_ = des::Time::max();
  std::deque<des::Time> misses_;
  des::Time last_display_ = des::Time::ps(-1);
};

}  // namespace

std::unique_ptr<AppPacer> make_just_in_time_pacer(const JustInTimeParams& p) {
  return std::make_unique<JustInTimePacer>(p);
}

std::unique_ptr<AppPacer> make_miss_rate_pacer(const MissRateParams& p) { return std::make_unique<MissRatePacer>(p); }

}  // namespace latsim::pipelines::frame_stages
