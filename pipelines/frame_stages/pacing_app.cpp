// Application pacing: the plan shared by every policy, and Monado's
// u_pacing_app (docs/pacing.md: the algorithm as Monado documents and
// publishes it, re-derived here; no code of Monado's).
#include <algorithm>
#include <cmath>

#include "frame_stages/pacing.hpp"
#include "frame_stages/pacing_jit.hpp"
#include "frame_stages/pacing_runtime_pacers.hpp"

namespace latsim::pipelines::frame_stages {

des::Time FrameSample::longest_span() const { return std::max({cpu, draw, gpu}); }

FramePlan plan_for(des::Time now, des::Time app_time, des::Time margin, int frame_periods, des::Time last_display,
                   const PacingClock& clock) {
  const des::Time comp = clock.compositor_time();
  const des::Time lead = app_time + margin + comp;
  des::Time earliest = now + lead;
  if (last_display >= des::Time::zero()) {
    // Retraces are not whole picoseconds apart: aim half a period early and
    // let next_display round up to the retrace itself.
    const des::Time spaced = last_display + clock.period * frame_periods - des::Time::ps(clock.period.ticks() / 2);
    earliest = std::max(earliest, spaced);
  }
  FramePlan p;
  p.display = clock.next_display(earliest);
  p.latch = p.display - comp;
  p.wake_up = p.latch - margin - app_time;
  p.predicted_done = p.wake_up + app_time;
  p.frame_periods = frame_periods;
  return p;
}

namespace {

/// u_pacing_app: the CPU, draw and GPU times each smoothed by an IIR filter;
/// the frame period the display period stepped up until it covers each; the
/// display time the first one the application time, the margin and the
/// compositor's time fit before.
class MonadoAppPacer final : public AppPacer {
 public:
  explicit MonadoAppPacer(const MonadoAppParams& p) : p_(p), cpu_(p.initial), draw_(p.initial), gpu_(p.initial_gpu) {}

  FramePlan plan(des::Time now, const PacingClock& clock) override {
    const des::Time app = std::max(p_.min_app_time, cpu_ + draw_ + gpu_);
    int periods = 1;
    while (clock.period * periods < std::max({cpu_, draw_, gpu_})) ++periods;
    periods = std::max(periods, clock.period_multiple);
    const FramePlan plan = plan_for(now, app, p_.margin, periods, last_display_, clock);
    last_display_ = plan.display;
    return plan;
  }

  void measured(const FrameSample& s) override {
    cpu_ = smooth(cpu_, s.cpu);
    draw_ = smooth(draw_, s.draw);
    gpu_ = smooth(gpu_, s.gpu);
  }

 private:
  des::Time smooth(des::Time old, des::Time sample) const {
    const double v = p_.iir_weight * static_cast<double>(old.ticks()) +
                     (1.0 - p_.iir_weight) * static_cast<double>(sample.ticks());
    return des::Time::ps(std::llround(v));
  }

  MonadoAppParams p_;
  des::Time cpu_, draw_, gpu_;
  des::Time last_display_ = des::Time::ps(-1);
};

}  // namespace

std::unique_ptr<AppPacer> make_app_pacer(const PacingSpec& spec) {
  switch (spec.app) {
    case AppPolicy::fixed: return nullptr;
    case AppPolicy::monado: return std::make_unique<MonadoAppPacer>(spec.monado);
    case AppPolicy::just_in_time: return make_just_in_time_pacer(spec.just_in_time);
    case AppPolicy::miss_rate: return make_miss_rate_pacer(spec.miss_rate);
    case AppPolicy::steamvr: return make_steamvr_pacer(spec.steamvr);
    case AppPolicy::oculus: return make_oculus_pacer(spec.oculus);
  }
  return nullptr;
}

}  // namespace latsim::pipelines::frame_stages
