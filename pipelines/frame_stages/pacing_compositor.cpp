#include "frame_stages/pacing_compositor.hpp"

#include <algorithm>
#include <cmath>

namespace latsim::pipelines::frame_stages {

CompositorPacer::CompositorPacer(const CompositorPacingParams& p, des::Time period, const WarpClock& clock)
    : p_(p), period_(period), clock_(clock) {
  budget_ = percent_of_period(p.initial_percent);
  max_ = percent_of_period(p.max_percent);
  miss_step_ = percent_of_period(p.miss_step_percent);
  step_ = percent_of_period(p.step_percent);
}

des::Time CompositorPacer::percent_of_period(double percent) const {
  return des::Time::ps(std::llround(static_cast<double>(period_.ticks()) * percent / 100.0));
}

des::Time CompositorPacer::wake_up(JobRecord& rec, des::Time now) {
  // Monado walks forward while desired_present <= now + comp_time + margin:
  // the deadline is the first strictly after that instant.
  const des::Time lead = this->lead();
  des::Time d = clock_.next_deadline(now + lead + des::Time::ps(1));
  while (d <= last_deadline_) d = clock_.next_deadline(d + des::Time::ps(1));
  last_deadline_ = d;
  rec.deadline = d;
  return d - lead;
}

void CompositorPacer::on_complete(const JobRecord& rec, results::LatencyRecorder& recorder) {
  if (rec.skipped) return;
  const des::Time done = rec.end.back();
  // Done after its deadline, the warp is shown at the next one.
  const des::Time shown = done <= rec.deadline ? rec.deadline : clock_.next_deadline(done);
  const des::Time margin = rec.deadline - done;
  recorder.add("compositor_budget_ms", budget_.to_ms());
  recorder.add("compositor_margin_ms", margin.to_ms());
  if (shown - rec.deadline >= p_.late_slop) {
    // adjust_comp_time's miss branch: the one place the budget is capped.
    ++misses_;
    budget_ = std::min(max_, budget_ + miss_step_);
    return;
  }
  const des::Time off = margin - p_.target_margin;
  if (off < step_ && -off < step_) return;  // within the band
  if (off > des::Time::zero()) budget_ -= step_;
  else budget_ += step_;
}

void CompositorPacer::finish(results::LatencyRecorder& r) const { r.set("compositor_misses", misses_); }

}  // namespace latsim::pipelines::frame_stages
