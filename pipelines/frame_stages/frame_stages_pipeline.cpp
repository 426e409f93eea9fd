#include "frame_stages/frame_stages_pipeline.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>

#include "latsim/sections/render_cost.hpp"
#include "frame_stages/app_frame_times.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/results/frame_recorder.hpp"
#include "latsim/results/figure_writer.hpp"

namespace latsim::pipelines::frame_stages {

FrameStagesPipeline::FrameStagesPipeline(const Params& params) : spec_(params.spec) {}

FrameStagesPipeline::~FrameStagesPipeline() = default;

FlowEnv FrameStagesPipeline::env(des::RandomStream& stream) {
  FlowEnv e{ctx_->sim, {}, {}, {}, *retraces_, {}, *poses_, stream, ctx_->timeline};
  for (size_t i = 0; i < processors_.size(); ++i) {
    e.processors.push_back(processors_[i].get());
    e.processor_names.push_back(spec_.processors[i].name);
    e.preemption_slices.push_back(spec_.processors[i].preemption_slice);
  }
  const display::RasterTiming* timing = &ctx_->display.timing();
  e.next_retrace = [timing](des::Time t) { return timing->field_start(timing->field_at_or_after(t)); };
  e.out_of_input = [ctx = ctx_](const renderer::RenderCost& cost) {
    ctx->end_run_early(sections::trace_ran_out(cost, ctx->sim.now()));
  };
  return e;
}

des::Time FrameStagesPipeline::app_photon_target(des::Time completion) const {
  // Without vsync a frame is shown at once: it first appears on the line
  // the beam writes next, lit as the display lights that line (the runtime
  // knows the display's timing and its expected completion). Otherwise from
  // the next retrace, the middle line as its centre.
  if (!spec_.vsync && !spec_.warp) return ctx_->first_line_photon_time(completion);
  return ctx_->photon_time_after(completion);
}

FlowHooks FrameStagesPipeline::app_hooks() {
  FlowHooks h;
  h.max_in_flight = spec_.max_frames_in_flight;
  const display::RasterTiming* timing = &ctx_->display.timing();
  h.next_deadline = [timing](des::Time t) { return timing->field_start(timing->field_at_or_after(t)); };
  h.photon_for_completion = [this](des::Time t) { return app_photon_target(t); };
  h.image_buffers = image_buffers_.get();
  h.on_complete = [this](JobRecord& frame) {
    ctx_->app_frames.rendered(app_frame_times(frame, app_->last_run_first()));
    // What a runtime calls its prediction time: the pose query to the photon time it asked for.
    if (frame.last_pose && !frame.skipped)
      ctx_->figures.add("query_to_photon_ms", (frame.last_pose->target - frame.last_sample_at).to_ms());
    if (compositor_) compositor_->on_frame_complete(frame);
    else swap_chain_->on_frame_complete(frame);
    if (app_pacing_) app_pacing_->on_complete(frame);
  };
  if (app_pacing_) h.wake_up = [this](JobRecord& frame, des::Time now) { return app_pacing_->wake_up(frame, now); };
  h.retrace_divider = spec_.warp && spec_.warp->half_rate ? 2 : 1;
  h.frame_period = (timing->field_start(1) - timing->field_start(0)) * h.retrace_divider;
  return h;
}

FlowHooks FrameStagesPipeline::warp_hooks() {
  FlowHooks h;
  h.max_in_flight = 1;
  const WarpClock* clock = &compositor_->clock();
  h.next_deadline = [clock](des::Time t) { return clock->next_deadline(t); };
  h.photon_for_completion = [clock, ctx = ctx_](des::Time t) {
    const WarpClock::Slot slot = clock->slot_of(clock->next_deadline(t));
    return ctx->photon_time(slot.field, clock->middle_line(slot.strip));
  };
  h.on_begin = [this](JobRecord& warp) { return compositor_->on_begin(warp); };
  h.on_complete = [this](JobRecord& warp) {
    compositor_->on_complete(warp);
    if (compositor_pacer_) compositor_pacer_->on_complete(warp, ctx_->figures);
  };
  if (compositor_pacer_)
    h.wake_up = [this](JobRecord& warp, des::Time now) { return compositor_pacer_->wake_up(warp, now); };
  return h;
}

void FrameStagesPipeline::start(RunContext& ctx) {
  ctx_ = &ctx;
  ctx.signals.shows_images();
  // With a compositor every frame waits for a warp at a retrace (or strip).
  const bool synced = spec_.vsync || spec_.warp;
  // Beam racing renders every strip itself: the application's frames are never shown.
  const bool shown = !spec_.warp || spec_.warp->mode != WarpSpec::Mode::render;
  ctx.app_frames.declare({.missed = true, .rate = true},
                         {.sync_interval = synced ? 1 : 0, .allows_tearing = !synced, .shown = shown});
  for (const ProcessorSpec& p : spec_.processors) processors_.push_back(std::make_unique<des::Resource>(ctx.sim, 1, p.name));
  retraces_ = std::make_unique<Progress>(ctx.sim);
  poses_ = std::make_unique<PoseSampler>(ctx.host);
  app_stream_ = std::make_unique<des::RandomStream>(ctx.stream("frame_stages"));
  if (spec_.warp) {
    image_buffers_ = std::make_unique<des::Resource>(ctx.sim, spec_.warp->eye_buffers, "eye_buffers");
    compositor_ = std::make_unique<Compositor>(ctx, *spec_.warp, *image_buffers_);
    residuals_ = std::make_unique<ResidualErrors>(*compositor_, ctx.images, ctx.figures, ctx.motion, ctx.ipd_m, ctx.stereo);
    ctx.display.add_listener(residuals_.get());
  } else {
    image_buffers_ = std::make_unique<des::Resource>(ctx.sim, spec_.swap_chain_images, "swap_chain");
    swap_chain_ = std::make_unique<SwapChain>(ctx, *image_buffers_, spec_.vsync);
  }
  start_pacing(ctx);
  app_ = std::make_unique<StageFlow>("frame.stage", spec_.stages, spec_.late, env(*app_stream_), app_hooks());
  if (spec_.warp) {
    warp_stream_ = std::make_unique<des::RandomStream>(ctx.stream("compositor"));
    FlowEnv warp_env = env(*warp_stream_);
    warp_env.yields = false;  // the compositor preempts; it is not preempted
    warp_ = std::make_unique<StageFlow>("compositor.warp", spec_.warp->stages, spec_.late, std::move(warp_env),
                                        warp_hooks());
  }
  // The swap happens before the waiting threads are told of the retrace.
  ctx.display.on_retrace([this](int64_t field, des::Time) {
    if (swap_chain_) swap_chain_->on_retrace(field);
    retraces_->raise_to(field + 1);
  });
  app_->start();
  if (warp_) warp_->start();
}

void FrameStagesPipeline::warn_about_overload(RunContext& ctx) const {
  // Behind a compositor the display shows a (re-warped) image at every
  // refresh, so missed_refreshes and frame_rate_hz look healthy while the
  // application falls behind: say so, in the application's own terms.
  results::FigureWriter& r = ctx.figures;
  const double seconds = ctx.sim.now().to_seconds();
  const int64_t missed = ctx.app_frames.frames_missed();
  if (missed > 0 && seconds > 0) {
    char rates[96];
    std::snprintf(rates, sizeof rates, "%.1f Hz against the display's %.1f Hz",
                  static_cast<double>(ctx.app_frames.frames_rendered()) / seconds,
                  1.0 / (ctx.display.timing().field_start(1) - ctx.display.timing().field_start(0)).to_seconds());
    r.warn("the application missed " + std::to_string(missed) + " refreshes it was paced for (frames_missed) and " +
           "rendered at " + rates + " (application_frame_rate_hz); the compositor re-warped older images");
  }
  const int64_t late = compositor_->warps_late();
  if (late > 0) {
    std::string advice;
    for (const StageSpec& st : spec_.warp->stages)
      for (const int k : st.processors)
        if (spec_.processors[static_cast<size_t>(k)].preemption_slice == des::Time::zero() && advice.empty())
          advice = "; processor \"" + spec_.processors[static_cast<size_t>(k)].name +
                   "\" runs the warp without preemption_slice_ms, so a warp waits for the stage it shares it with";
    r.warn(std::to_string(late) + " of " + std::to_string(compositor_->warps()) +
           " warps ended after their retrace (warps_late)" + advice);
  }
}

void FrameStagesPipeline::start_pacing(RunContext& ctx) {
  const display::RasterTiming* timing = &ctx.display.timing();
  const des::Time period = timing->field_start(1) - timing->field_start(0);
  if (compositor_ && spec_.pacing.compositor.enabled)
    compositor_pacer_ = std::make_unique<CompositorPacer>(spec_.pacing.compositor, period, compositor_->clock());
  if (spec_.pacing.app == AppPolicy::fixed) return;
  PacingClock clock;
  clock.period = period;
  clock.period_multiple = spec_.warp && spec_.warp->half_rate ? 2 : 1;
  clock.next_display = [timing](des::Time t) { return timing->field_start(timing->field_at_or_after(t)); };
  // The compositor latches its lead (Monado: budget and margin; else the late warp's) before the
  // retrace; a swap chain at the retrace.
  clock.compositor_time = [this] {
    if (compositor_pacer_) return compositor_pacer_->lead();
    return warp_ ? warp_->late_lead(0) : des::Time::zero();
  };
  for (const StageSpec& st : spec_.stages) clock.handovers += st.start == StartRule::next_frame ? 1 : 0;
  std::function<void(bool)> set_half_rate;
  if (compositor_) {
    set_half_rate = [this](bool on) { compositor_->set_half_rate(on); };
    clock.set_planned_showings = [this](int n) { compositor_->set_planned_showings(n); };
  }
  app_pacing_ = std::make_unique<AppPacing>(spec_.pacing, spec_.stages, std::move(clock), ctx.figures, ctx.timeline,
                                            std::move(set_half_rate));
}

void FrameStagesPipeline::finish(RunContext& ctx) {
  results::FigureWriter& r = ctx.figures;
  const double refresh_hz = 1.0 / ctx.display_params.raster.field_period.to_seconds();
  for (const StageFlow* flow : {app_.get(), warp_.get()})
    if (flow)
      for (const StageSpec& st : flow->stages())
        if (st.cost.trace()) {
          r.add_capture(sections::trace_summary(st.cost));
          for (const std::string& w : sections::trace_warnings(st.cost, refresh_hz)) r.warn(w);
        }
  if (app_pacing_) app_pacing_->finish(r);
  if (compositor_pacer_) compositor_pacer_->finish(r);
  // frames_rendered, application_frame_rate_hz and frames_missed are ctx.app_frames'.
  // What an engineer of such a system reads first: behind a warp, the
  // latency of the orientation the warp used (the application pose's
  // motion-to-photon includes a whole frame the warp hides), and the
  // application's own pace, not the display's.
  if (swap_chain_) {
    r.use_headline("frame_stages");
    return;
  }
  r.use_headline("time_warp");
  warn_about_overload(ctx);
  r.set("frames_shown", compositor_->frames_shown());
  r.set("frames_rewarped", compositor_->frames_rewarped());
  r.set("frames_synthesised", compositor_->frames_synthesised());
  r.set("warps", compositor_->warps());
  r.set("warps_late", compositor_->warps_late());
  r.set("refreshes_without_image", compositor_->refreshes_without_image());
  r.set("refreshes_without_warp",
        compositor_->refreshes_without_warp(ctx.display.timing().field_at_or_after(ctx.sim.now())));
  r.list("residual_by_rewarps");
  int row = 0;
  for (size_t k = 0; k < residuals_->by_rewarps().size(); ++k) {
    const ResidualErrors::Bucket& b = residuals_->by_rewarps()[k];
    if (b.samples() == 0) continue;
    const std::string at = "residual_by_rewarps." + std::to_string(row++) + ".";
    r.set(at + "rewarps", static_cast<int64_t>(k));
    r.set(at + "spans", b.samples());  // latency samples: one per line, or per pixel_stride pixels
    r.set(at + "orientation_deg_mean", b.orientation_deg.mean());
    r.set(at + "position_mm_mean", b.position_mm.mean());
  }
}

}  // namespace latsim::pipelines::frame_stages
