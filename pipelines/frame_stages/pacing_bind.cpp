#include "frame_stages/pacing_bind.hpp"
#include "frame_stages/pacing_runtime_bind.hpp"

#include "latsim/scenario/readable.hpp"

namespace latsim::pipelines::frame_stages {

namespace {

using scenario::Section;

void bind(Section& s, MonadoAppParams& p) {
  s.number("iir_weight", p.iir_weight,
           {.min = 0.0, .max = 1.0, .doc = "each of the CPU, draw and GPU estimates: weight * old + (1 - weight) * sample"});
  s.duration("initial_ms", p.initial, {.unit = "ms", .min = 0.0, .doc = "the CPU and draw estimates before the first frame"});
  s.duration("initial_gpu_ms", p.initial_gpu,
             {.unit = "ms", .min = 0.0, .doc = "the GPU estimate before the first frame (Monado leaves it at zero)"});
  s.duration("min_app_time_ms", p.min_app_time, {.unit = "ms", .min = 0.0, .doc = "floor of the application time (their sum)"});
  s.duration("margin_ms", p.margin, {.unit = "ms", .min = 0.0, .doc = "between the predicted GPU end and the compositor's latch"});
}

void bind(Section& s, JustInTimeParams& p) {
  s.number("percentile", p.percentile, {.min = 0.0, .max = 100.0, .doc = "of the last `window` frame times (nearest rank)"});
  s.integer("window", p.window, {.min = 1.0, .max = 100000.0, .doc = "measured frame times (wake-up to GPU end) remembered"});
  s.duration("margin_ms", p.margin, {.unit = "ms", .min = 0.0, .doc = "added to the percentile"});
}

void bind(Section& s, MissRateParams& p) {
  s.number("target_per_min", p.target_per_min, {.min = 0.0, .doc = "missed latches per minute to stay below"});
  s.number("window_s", p.window_s, {.unit = "s", .min = 0.0, .max = 3600.0, .above_min = true, .doc = "misses counted over the last this long"});
  s.integer("median_window", p.median_window, {.min = 1.0, .max = 100000.0, .doc = "frame times the median is taken over"});
  s.duration("initial_margin_ms", p.initial_margin, {.unit = "ms", .min = 0.0, .doc = "the margin before any frame"});
  s.duration("raise_ms", p.raise, {.unit = "ms", .min = 0.0, .doc = "added to the margin at each miss"});
  s.duration("lower_ms", p.lower, {.unit = "ms", .min = 0.0, .doc = "taken off per frame on time while the rate is below target"});
}

void bind(Section& s, HalfRateFallbackParams& p) {
  s.integer("misses", p.misses, {.min = 1.0, .max = 1000.0, .doc = "misses among the last `window` frames that force half rate"});
  s.integer("window", p.window, {.min = 1.0, .max = 1000.0, .doc = "frames looked back at"});
  s.integer("clean_frames", p.clean_frames,
            {.min = 1.0, .max = 100000.0,
             .doc = "consecutive frames whose measured time (longest span) fits the full-rate budget less the "
                    "return margin that return to full rate"});
  s.number("return_margin_percent", p.return_margin_percent,
           {.min = 0.0, .max = 100.0,
            .doc = "% of the refresh period the measured time must leave spare in the full-rate budget (the period "
                   "less the compositor's time) before returning"});
}

void bind(Section& s, CompositorPacingParams& p) {
  s.number("initial_percent", p.initial_percent, {.min = 0.0, .max = 100.0, .doc = "first budget, % of the refresh period"});
  s.number("max_percent", p.max_percent,
           {.min = 0.0, .max = 100.0, .doc = "ceiling of the budget after a miss's step, % of the period"});
  s.number("miss_step_percent", p.miss_step_percent, {.min = 0.0, .max = 100.0, .doc = "added after a miss, % of the period"});
  s.number("step_percent", p.step_percent,
           {.min = 0.0, .max = 100.0, .doc = "step towards the target margin and the band's half width, % of the period"});
  s.duration("target_margin_ms", p.target_margin, {.unit = "ms", .min = 0.0, .doc = "wanted between the warp's end and its deadline"});
  s.duration("late_slop_ms", p.late_slop,
             {.unit = "ms", .min = 0.0, .doc = "shown this much or more after the deadline: a miss"});
}

}  // namespace

void bind_pacing(Section& s, PacingKeys& k) {
  PacingSpec& p = k.spec;
  s.choice("application", p.app,
           {{"fixed", AppPolicy::fixed},
            {"monado", AppPolicy::monado},
            {"just_in_time", AppPolicy::just_in_time},
            {"miss_rate", AppPolicy::miss_rate},
            {"steamvr", AppPolicy::steamvr},
            {"oculus", AppPolicy::oculus}},
           {.doc = "fixed: the first stage's own start rule (today's behaviour); monado: Monado's u_pacing_app (IIR "
                   "CPU, draw and GPU times); just_in_time: a percentile of recent frame times plus a margin before "
                   "the latch (Phase Sync, Reflex); miss_rate: a margin controlled to hold missed latches per minute "
                   "below a target; steamvr: SteamVR's running start and throttling; oculus: Phase Sync with ASW. "
                   "See docs/pacing.md"});
  s.object("monado", p.monado, [](Section& e, MonadoAppParams& v) { bind(e, v); }, {.doc = "application: monado"});
  s.object("just_in_time", p.just_in_time, [](Section& e, JustInTimeParams& v) { bind(e, v); },
           {.doc = "application: just_in_time"});
  s.object("miss_rate", p.miss_rate, [](Section& e, MissRateParams& v) { bind(e, v); }, {.doc = "application: miss_rate"});
  bind_runtime_pacing(s, p);
  s.text("draw_stage", k.draw_stage,
         {.doc = "first stage of the measured draw span (default: the first of the run before the GPU span's)"});
  s.text("gpu_stage", k.gpu_stage, {.doc = "first stage of the measured GPU span (default: the first of the last run)"});
  std::optional<HalfRateFallbackParams> fallback;
  s.optional_object("half_rate_fallback", fallback, [](Section& e, HalfRateFallbackParams& v) { bind(e, v); },
                    {.doc = "after repeated misses the application runs at half rate and the compositor synthesises "
                            "every other refresh, until a run of frames on time (needs a paced application and a timewarp)"});
  if (fallback) {
    p.half_rate = *fallback;
    p.half_rate.enabled = true;
  }
  bool monado_compositor = false;
  s.choice("compositor", monado_compositor, {{"late", false}, {"monado", true}},
           {.doc = "late: the warp's own late rule; monado: Monado's u_pacing_compositor budget with display-timing "
                   "feedback (needs a timewarp)"});
  s.object("compositor_monado", p.compositor, [](Section& e, CompositorPacingParams& v) { bind(e, v); },
           {.doc = "compositor: monado"});
  p.compositor.enabled = monado_compositor;
  s.rule("half_rate_fallback", "needs an application policy other than fixed, and a timewarp");
  s.rule("compositor", "monado needs a timewarp");
}

void resolve_pacing(Section& s, PacingKeys& k, const std::vector<StageSpec>& stages, bool has_warp) {
  const std::string base = s.pointer() + "/pacing";
  auto index_of = [&](const std::string& key, const std::string& name) {
    if (name.empty()) return -1;
    for (size_t i = 0; i < stages.size(); ++i)
      if (stages[i].name == name) return static_cast<int>(i);
    s.check_pointer(base + "/" + key, false, "no stage is named " + scenario::quote_value(name));
    return -1;
  };
  k.spec.stages.draw = index_of("draw_stage", k.draw_stage);
  k.spec.stages.gpu = index_of("gpu_stage", k.gpu_stage);
  s.check_pointer(base + "/draw_stage",
                  k.spec.stages.draw < 0 || k.spec.stages.gpu < 0 || k.spec.stages.draw <= k.spec.stages.gpu,
                  "the draw span begins no later than the GPU span");
  s.check_pointer(base + "/half_rate_fallback",
                  !k.spec.half_rate.enabled || (has_warp && k.spec.app != AppPolicy::fixed),
                  "half-rate fallback needs an application policy other than fixed and a timewarp");
  s.check_pointer(base + "/compositor", !k.spec.compositor.enabled || has_warp, "monado compositor pacing needs a timewarp");
}

void bind_cost_shape(Section& s, CostShape& shape) {
  std::vector<std::vector<double>> steps;
  s.number_rows("steps", steps,
                {.count = 2, .doc = "[frame, ms] rows: from that frame on the stage takes that long (replaces the cost)"});
  s.number("spike_probability", shape.spike_probability, {.min = 0.0, .max = 1.0, .doc = "chance that a frame spikes"});
  s.duration("spike_ms", shape.spike, {.unit = "ms", .min = 0.0, .doc = "added to a spiking frame"});
  s.rule("steps", "frames in increasing order, from 0 to 1e15; durations from 0 to 1e6 ms");
  if (s.describing()) return;
  shape.steps.clear();
  for (size_t i = 0; i < steps.size(); ++i) {
    const std::string at = s.pointer() + "/steps/" + std::to_string(i);
    s.check_pointer(at, steps[i][0] >= 0.0 && steps[i][1] >= 0.0, "a frame and a duration, neither negative");
    s.check_pointer(at, steps[i][0] <= 1e15 && steps[i][1] <= 1e6, "at most frame 1e15 and 1e6 ms");
    s.check_pointer(at, i == 0 || steps[i][0] > steps[i - 1][0], "frames in increasing order");
    shape.steps.emplace_back(static_cast<int64_t>(steps[i][0]), des::Time::from_ms(steps[i][1]));
  }
}

}  // namespace latsim::pipelines::frame_stages
