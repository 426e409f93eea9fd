#include "frame_stages/pacing_driver.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace latsim::pipelines::frame_stages {

PacingStages resolve_pacing_stages(const PacingStages& given, const std::vector<StageSpec>& stages) {
  std::vector<int> run_starts;
  for (size_t i = 0; i < stages.size(); ++i)
    if (i == 0 || stages[i - 1].processors != stages[i].processors) run_starts.push_back(static_cast<int>(i));
  PacingStages out = given;
  if (out.gpu < 0) out.gpu = run_starts.back();
  if (out.draw < 0) {
    auto it = std::find(run_starts.begin(), run_starts.end(), out.gpu);
    out.draw = it != run_starts.end() && it != run_starts.begin() ? *(it - 1) : out.gpu;
  }
  out.draw = std::min(out.draw, out.gpu);
  return out;
}

AppPacing::AppPacing(const PacingSpec& spec, const std::vector<StageSpec>& stages, PacingClock clock,
                     results::FigureWriter& figures, results::Timeline* timeline,
                     std::function<void(bool)> set_half_rate)
    : fallback_(spec.half_rate),
      pacer_(make_app_pacer(spec)),
      clock_(std::move(clock)),
      figures_(figures),
      timeline_(timeline),
      set_half_rate_(std::move(set_half_rate)) {
  const PacingStages s = resolve_pacing_stages(spec.stages, stages);
  draw_ = s.draw;
  gpu_ = s.gpu;
}

des::Time AppPacing::wake_up(JobRecord& rec, des::Time now) {
  const FramePlan plan = pacer_->plan(now, clock_);
  plans_[rec.job] = plan;
  planned_half_[rec.job] = half_rate();
  rec.deadline = plan.latch;
  if (plan.hold) rec.not_before = plan.display;
  return plan.wake_up;
}

FrameSample AppPacing::measure(const JobRecord& rec, const FramePlan& plan) const {
  // cpu: woken to the draw span; draw: its start to the end of the stage
  // before the GPU span (the submission); gpu: from there to the GPU's end.
  FrameSample s;
  s.woke = rec.released.front();
  s.gpu_done = rec.end.back();
  const size_t draw = static_cast<size_t>(draw_), gpu = static_cast<size_t>(gpu_);
  const des::Time submitted = gpu > 0 ? std::max(rec.end[gpu - 1], s.woke) : s.woke;
  const des::Time draw_start = draw < gpu ? rec.start[draw] : submitted;
  s.cpu = std::max(des::Time::zero(), draw_start - s.woke);
  s.draw = std::max(des::Time::zero(), submitted - draw_start);
  s.gpu = std::max(des::Time::zero(), s.gpu_done - submitted);
  s.latch = plan.latch;
  s.missed = s.gpu_done > plan.latch;
  return s;
}

void AppPacing::on_complete(const JobRecord& rec) {
  auto it = plans_.find(rec.job);
  if (it == plans_.end() || rec.skipped) return;
  const FramePlan plan = it->second;
  const bool half = planned_half_[rec.job];
  plans_.erase(it);
  planned_half_.erase(rec.job);
  const FrameSample s = measure(rec, plan);
  pacer_->measured(s);
  figures_.add("wake_up_error_ms", (s.gpu_done - plan.predicted_done).to_ms());
  figures_.add("latch_slack_ms", (plan.latch - s.gpu_done).to_ms());
  if (s.missed) ++misses_;
  const des::Time comp = clock_.compositor_time();
  const des::Time shown = clock_.next_display(s.gpu_done + comp);
  if (timeline_) {
    timeline_->add("paced", rec.job, -1, "app pacing", plan.wake_up, plan.display);
    timeline_->add("shown", rec.job, -1, "app display", s.gpu_done, shown);
  }
  if (log_.size() < kMaxLog) log_.push_back(PacedFrame{rec.job, plan, s, shown, half});
  if (fallback_.enabled) fall_back(s);
}

void AppPacing::fall_back(const FrameSample& s) {
  if (!half_rate()) {
    recent_misses_.push_back(s.missed);
    if (static_cast<int>(recent_misses_.size()) > fallback_.window) recent_misses_.pop_front();
    if (std::count(recent_misses_.begin(), recent_misses_.end(), true) < fallback_.misses) return;
    clock_.period_multiple = 2;
    ++half_rate_periods_;
    fitting_run_ = 0;
    recent_misses_.clear();
    if (set_half_rate_) set_half_rate_(true);
    return;
  }
  ++half_rate_frames_;
  // Hysteresis: a frame on time at half rate says nothing of full rate; only
  // a measured time that fits a refresh with the margin to spare does.
  fitting_run_ = s.longest_span() <= return_threshold() ? fitting_run_ + 1 : 0;
  if (fitting_run_ < fallback_.clean_frames) return;
  clock_.period_multiple = 1;
  if (set_half_rate_) set_half_rate_(false);
}

des::Time AppPacing::return_threshold() const {
  const des::Time margin = des::Time::ps(
      std::llround(static_cast<double>(clock_.period.ticks()) * fallback_.return_margin_percent / 100.0));
  return clock_.period - clock_.compositor_time() - margin;
}

void AppPacing::finish(results::FigureWriter& r) const {
  r.set("frames_late_to_latch", misses_);
  for (const auto& [name, value] : pacer_->counters()) r.set(name, value);
  if (!fallback_.enabled) return;
  r.set("half_rate_periods", half_rate_periods_);
  r.set("half_rate_frames", half_rate_frames_);
}

}  // namespace latsim::pipelines::frame_stages
