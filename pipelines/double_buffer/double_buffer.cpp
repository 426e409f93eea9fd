// Conventional double buffering: render with the newest pose, swap at the next
// retrace after completion; optionally render ahead with N frames queued, or
// swap at once without vsync (tearing).
#include <algorithm>
#include <deque>
#include <limits>
#include <memory>

#include "double_buffer/analytic.hpp"
#include "latsim/des/handoff.hpp"
#include "latsim/des/process.hpp"
#include "latsim/des/run_clocks.hpp"
#include "latsim/sections/render_cost.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/results/frame_recorder.hpp"
#include "latsim/results/figure_writer.hpp"
#include "latsim/results/timeline.hpp"

namespace latsim::pipelines {

namespace {

/// Renders frames back to back on one renderer and hands them to the display.
class DoubleBufferPipeline final : public Pipeline {
 public:
  struct Params {
    bool vsync = true;
    int queued_frames = 0;
    renderer::RenderCost::Params render;
    renderer::RenderCost cost;  ///< the render terms applied to the scene and display
  };

  explicit DoubleBufferPipeline(const Params& p) : p_(p) {}

  void start(RunContext& ctx) override {
    ctx_ = &ctx;
    stream_ = std::make_unique<des::RandomStream>(ctx.stream("renderer"));
    const des::KindId kind_frame = ctx.sim.kind("renderer.frame");
    ctx.signals.shows_images();
    ctx.app_frames.declare({}, {.sync_interval = p_.vsync ? 1 : 0, .allows_tearing = !p_.vsync});
    if (p_.vsync) ctx.display.on_retrace([this](int64_t, des::Time now) { retrace(now); });
    ctx.sim.start(renderer(), kind_frame);
  }

  // One event per frame (its render delay; a retrace resumes the renderer
  // within the display's event). With vsync at most one frame per refresh
  // leaves the swap queue; without, frames follow each other back to back.
  std::vector<EventRate> event_rates(const sections::SharedParams& shared) const override {
    const des::Time frame = p_.cost.nominal_frame_time();
    const double fields_per_s = 1.0 / shared.display.raster.field_period.to_seconds();
    if (!p_.vsync) return {{"/pipeline/render", "renderer", paced_per_s(frame, std::numeric_limits<double>::infinity())}};
    const bool render_bound = frame.to_seconds() * fields_per_s > 1.0;
    return {{render_bound ? "/pipeline/render" : "/display/refresh_hz", "renderer", paced_per_s(frame, fields_per_s)}};
  }

  void finish(RunContext& ctx) override {
    ctx.figures.set("nominal_frame_time_ms", p_.cost.nominal_frame_time().to_ms());
    ctx.figures.use_headline("double_buffer");
    if (p_.cost.trace()) {
      ctx.figures.add_capture(sections::trace_summary(p_.cost));
      const double refresh_hz = 1.0 / ctx.display_params.raster.field_period.to_seconds();
      for (const std::string& w : sections::trace_warnings(p_.cost, refresh_hz)) ctx.figures.warn(w);
    }
    if (!p_.vsync || p_.queued_frames != 0 || p_.cost.varies()) return;
    const auto a = analytic_double_buffer(analytic_inputs(ctx, p_.cost.nominal_frame_time()));
    if (!a) return;
    results::FigureWriter& r = ctx.figures;
    r.set("analytic.method", a->method);
    r.set("analytic.link", a->link);
    r.set("analytic.hyperperiod_s", a->hyperperiod_s);
    r.set("analytic.frames", a->frames);
    r.set("analytic.phase_grid", a->phase_grid);
    r.set("analytic.complete", a->complete);
    r.set("analytic.motion_to_photon_ms.min", a->min_ms);
    r.set("analytic.motion_to_photon_ms.mean", a->mean_ms);
    r.set("analytic.motion_to_photon_ms.max", a->max_ms);
  }

 private:
  struct Done {
    std::vector<int64_t> ids;
    int64_t frame;
    des::Time render_end;
  };

  // The renderer: wait for a pose, render, hand the image over; without
  // vsync it replaces the front buffer at once, otherwise it waits in the
  // swap queue and the renderer waits while the queue is full.
  des::Process renderer() {
    for (;;) {
      std::optional<tracker::PosePrediction> pose;
      while (!(pose = ctx_->host.pose_for(ctx_->sim.now(), expected_photon_time()))) {
        if (p_.vsync) co_await retrace_;  // retried at the next retrace
        else co_await ctx_->sim.delay(des::Time::ms(1));
      }
      const des::Time start = ctx_->sim.now();
      // With vsync every render aims at the next refresh.
      if (p_.vsync) ctx_->signals.image_due(start + des::Time::ps(1));
      // A measured cost with nothing left ends the run after this event.
      if (p_.cost.exhausted()) ctx_->end_run_early(sections::trace_ran_out(p_.cost, ctx_->sim.now()));
      const des::Time render_time = p_.cost.frame_time(*stream_);
      co_await ctx_->sim.delay(render_time);
      Done done = complete(*pose, start, render_time);
      if (!p_.vsync) {
        // No vsync: the new image replaces the front buffer mid-scan.
        for (int eye = 0; eye < ctx_->display.eyes(); ++eye) ctx_->display.present_now(eye, done.ids[eye]);
        ctx_->app_frames.flipped(done.frame, ctx_->sim.now());
        continue;
      }
      queue_.push_back(std::move(done));
      while (static_cast<int>(queue_.size()) > p_.queued_frames) co_await retrace_;
    }
  }

  // When a frame started now is expected to be lit: after its nominal render
  // time, at the next retrace behind the frames already queued (vsync: the
  // middle line's photon time), or on the first line the beam writes after
  // it (no vsync: the image appears there, mid-field).
  des::Time expected_photon_time() const {
    const des::Time now = ctx_->sim.now();
    const des::Time ready = now + p_.cost.nominal_frame_time();
    if (!p_.vsync) return ctx_->first_line_photon_time(ready);
    // Each queued image takes one of the retraces after now (the one at now,
    // if any, has already swapped).
    const display::RasterTiming& t = ctx_->display.timing();
    const int64_t first_free = t.field_at_or_before(now) + 1 + static_cast<int64_t>(queue_.size());
    return ctx_->frame_photon_time(std::max(t.field_at_or_after(ready), first_free));
  }

  Done complete(const tracker::PosePrediction& pose, des::Time start, des::Time render_time) {
    const des::Time now = ctx_->sim.now();
    Done done{{}, frame_, now};
    for (int eye = 0; eye < ctx_->display.eyes(); ++eye) {
      results::ImageRecord rec = ctx_->image_record(frame_, eye, pose, start, now);
      done.ids.push_back(ctx_->images.add(rec));
    }
    if (ctx_->timeline) ctx_->timeline->add("RENDER", frame_, -1, "renderer", start, now);
    // One renderer draws and hands the image over when done: GPU work only.
    results::FrameTimes times;
    times.frame = frame_;
    times.present = times.gpu_end = now;
    times.gpu_start = start;
    times.gpu_busy = render_time;
    ctx_->app_frames.rendered(times);
    ++frame_;
    return done;
  }

  // Called at the retrace before scanout: the swap takes effect for this field.
  void retrace(des::Time now) {
    if (!queue_.empty()) {
      const Done d = std::move(queue_.front());
      queue_.pop_front();
      for (int eye = 0; eye < ctx_->display.eyes(); ++eye) ctx_->display.present_now(eye, d.ids[eye]);
      ctx_->app_frames.flipped(d.frame, now);
      if (ctx_->timeline) ctx_->timeline->add("QUEUED", d.frame, -1, "swapchain", d.render_end, now);
    }
    retrace_.resume();
  }

  Params p_;
  RunContext* ctx_ = nullptr;
  std::unique_ptr<des::RandomStream> stream_;
  des::Handoff retrace_;
  std::deque<Done> queue_;
  int64_t frame_ = 0;
};

void bind(scenario::Section& s, DoubleBufferPipeline::Params& p, const sections::SharedParams& shared) {
  s.flag("vsync", p.vsync,
         {.doc = "swap at the next retrace after completion; false: swap at once (tearing; needs a render time above "
                 "zero)"});
  s.integer("queued_frames", p.queued_frames, {.min = 0.0, .max = 16.0, .doc = "render-ahead: frames that may wait for display"});
  s.object("render", p.render, [](scenario::Section& r, renderer::RenderCost::Params& v) { sections::bind(r, v); },
           {.required = true, .doc = "the renderer's cost per frame"});
  const display::RasterParams& raster = shared.display.raster;
  s.guard("render", [&] {
    p.cost = sections::render_cost_for_scene(p.render, shared.scene ? &*shared.scene : nullptr, raster.width_px,
                                           raster.height_px, shared.host.stereo ? 2 : 1);
  });
  s.check("vsync", p.vsync || p.cost.nominal_frame_time() > des::Time::zero(),
          "without vsync the renderer runs back to back, so frames need a render time above zero");
}

}  // namespace

PipelineEntry double_buffer_pipeline() {
  return pipeline_entry<DoubleBufferPipeline>(
      "double_buffer",
      "Conventional double buffering: render with the newest pose, swap at the next retrace after completion "
      "(optionally rendering ahead, or swapping at once without vsync). Where the configuration is tractable (no "
      "jitter, constant render time, vsync, no render-ahead, no queueing on the serial line) `figures.analytic` "
      "gives the min / mean / max motion-to-photon latency beside the simulated distribution: enumerated over one "
      "repeat cycle when every clock phase is fixed, otherwise integrated over the phases that vary between "
      "replications (see docs/figures.md).");
}

}  // namespace latsim::pipelines
