// The frameless pipeline's /pipeline keys and registry entry, its construction and its start.
#include "frameless/frameless_pipeline.hpp"

#include <algorithm>
#include <cmath>

#include "latsim/sections/shared.hpp"
#include "latsim/scenario/section.hpp"

namespace latsim::pipelines {

namespace frameless {

FramelessPipeline::FramelessPipeline(const Params& p)
    : double_buffer_(p.double_buffer),
      budget_px_s_(p.budget_px_s),
      budget_pointer_(p.pixels_per_s ? "/pipeline/pixels_per_s" : "/pipeline/full_images_per_s"),
      chunk_px_(p.chunk_pixels),
      depth_m_(p.registration_depth_m),
      fallback_(p.fallback ? p.fallback->kind : Mode::Normal),
      trigger_deg_(p.fallback ? p.fallback->trigger_deg : 20.0),
      trigger_m_(p.fallback ? p.fallback->trigger_m : 0.5),
      block_px_(p.fallback ? p.fallback->block_px : 4),
      sample_pixels_(p.sample_pixels),
      loop_(p.loop) {}

void FramelessPipeline::start(RunContext& ctx) {
  ctx_ = &ctx;
  size_to_display(ctx);
  const des::KindId kind_chunk = ctx.sim.kind("frameless.chunk");
  const des::KindId kind_image = ctx.sim.kind("frameless.image");
  // The computation runs from its own oscillator: its phase is drawn over
  // one full image (what double buffering shows), its rate error applies
  // to every pixel.
  const des::Clock& loop =
      ctx.clock("loop", "/pipeline/loop_phase_ms", des::RationalSeconds{pixels_, budget_px_s_}, loop_);
  schedule_ = des::PeriodicSchedule(ctx.sim.now() + loop.phase,
                                    des::period_with_rate_error({1, budget_px_s_}, loop.rate_error_ppm));
  pick_sampled_pixels(ctx.stream("frameless.samples"));
  ctx.display.add_listener(this);
  ctx.display.on_retrace([this](int64_t field, des::Time t) { retrace(field, t); });
  if (double_buffer_) {
    // Its first event, at the start of the budget, begins image 0.
    ctx.sim.spawn(images(), kind_image);
    return;
  }
  order_.emplace(pixels_, ctx.stream("frameless"));
  computed_.assign(static_cast<size_t>(pixels_), PixelState{});
  visible_ = computed_;
  stamp_.assign(static_cast<size_t>(pixels_), -1);
  if (fallback_ == Mode::LowResolution) make_blocks(ctx.stream("frameless.blocks"));
  if (fallback_ != Mode::Normal)
    ctx.host.on_delivery([this](const tracker::TrackerSample& s, des::Time t) { delivered(s, t); });
  if (ctx.frames) ctx.frames->set_pixel_source(this);
  ctx.sim.start(pixel_stream(), kind_chunk);
}

std::vector<EventRate> FramelessPipeline::event_rates(const sections::SharedParams& shared) const {
  const double budget = static_cast<double>(budget_px_s_);
  if (double_buffer_) {
    // One event per image of width × height × eyes pixels of the budget.
    const double pixels = static_cast<double>(shared.display.raster.width_px) * shared.display.raster.height_px *
                          (shared.host.stereo ? 2.0 : 1.0);
    return {{budget_pointer_, "frameless", budget / pixels}};
  }
  // One event per chunk; every pixel of the budget is computed (a step of work).
  std::vector<EventRate> out{{"/pipeline/chunk_pixels", "frameless", budget / static_cast<double>(chunk_px_)},
                             {budget_pointer_, "frameless", budget, true}};
  // A fallback watches every delivery of a tracker sample: one event each.
  if (fallback_ != Mode::Normal)
    out.push_back({"/tracker/rate_hz", "transport", 1.0 / shared.tracker.period.to_seconds()});
  return out;
}

void FramelessPipeline::size_to_display(RunContext& ctx) {
  width_ = ctx.display.timing().params().width_px;
  height_ = ctx.display.timing().params().height_px;
  eyes_ = ctx.display.eyes();
  pixels_ = static_cast<int32_t>(int64_t{width_} * height_ * eyes_);
  sampled_count_ = static_cast<int32_t>(std::min<int64_t>(sample_pixels_, pixels_));
  const double hfov_deg = ctx.display_params.hfov_deg;
  camera_.emplace(hfov_deg, width_, height_);
}

void FramelessPipeline::pick_sampled_pixels(des::RandomStream stream) {
  sampled_.assign(static_cast<size_t>(eyes_) * static_cast<size_t>(height_), {});
  const FramelessOrder pick(pixels_, std::move(stream));
  for (int32_t i = 0; i < sampled_count_; ++i) {
    const int32_t p = pick.pixel_of(i);
    sampled_[static_cast<size_t>(p / width_)].push_back(p % width_);
  }
  for (auto& xs : sampled_) std::sort(xs.begin(), xs.end());
}

void FramelessPipeline::make_blocks(des::RandomStream stream) {
  blocks_x_ = (width_ + block_px_ - 1) / block_px_;
  blocks_y_ = (height_ + block_px_ - 1) / block_px_;
  block_order_.emplace(blocks_x_ * blocks_y_ * eyes_, std::move(stream));
}

void bind(scenario::Section& s, FramelessPipeline::Params& p, const sections::SharedParams& shared) {
  s.choice("strategy", p.double_buffer, {{"frameless", false}, {"double_buffer", true}},
           {.doc = "frameless: each pixel from the newest pose; double_buffer: whole images at the same budget"});
  const int64_t pixels = int64_t{shared.display.raster.width_px} * shared.display.raster.height_px *
                         (shared.host.stereo ? 2 : 1);
  s.check("type", pixels <= int64_t{1} << 30, "frameless rendering supports at most 2^30 pixels (all eyes)");
  s.check("pixels_per_s", !(s.has("pixels_per_s") && s.has("full_images_per_s")),
          "give pixels_per_s or full_images_per_s, not both");
  s.number("pixels_per_s", p.pixels_per_s,
           {.unit = "px/s", .min = 0.0, .above_min = true, .doc = "pixel budget (instead of full_images_per_s)"});
  if (!p.pixels_per_s || s.describing())
    s.number("full_images_per_s", p.full_images_per_s,
             {.min = 0.0, .above_min = true, .doc = "pixel budget in whole images (width × height × eyes) per second"});
  const double budget = p.pixels_per_s ? *p.pixels_per_s : p.full_images_per_s * static_cast<double>(pixels);
  // Whole pixels per second keep the pixel schedule an exact rational period.
  p.budget_px_s = std::llround(budget);
  s.check(p.pixels_per_s ? "pixels_per_s" : "full_images_per_s", p.budget_px_s >= 1 && budget <= 1e12,
          "the pixel budget must lie between 1 and 1e12 pixels per second");
  s.integer("chunk_pixels", p.chunk_pixels,
            {.unit = "px", .min = 1.0, .max = 1073741824.0, .doc = "pixels computed per event (exact either way)"});
  s.integer("sample_pixels", p.sample_pixels,
            {.unit = "px", .min = 0.0, .max = 1073741824.0, .doc = "pixels where ages and registration are sampled"});
  sections::clock(s, "loop_", p.loop, "pixel computation (the first pixel's start)");
  s.number("registration_depth_m", p.registration_depth_m,
           {.unit = "m", .min = 0.0, .above_min = true, .doc = "depth at which a pixel's surface point is taken"});
  const bool double_buffer = p.double_buffer;
  using Fallback = FramelessPipeline::Params::Fallback;
  s.optional_object("fallback", p.fallback,
                    [double_buffer](scenario::Section& f, Fallback& v) {
                      f.doc("What frameless rendering does when the head moves fast.");
                      f.choice("kind", v.kind,
                               {{"none", Mode::Normal},
                                {"low_resolution", Mode::LowResolution},
                                {"double_buffer", Mode::DoubleBufferFallback}},
                               {.doc = "none, a low-resolution pass, or one whole image"});
                      f.number("trigger_deg", v.trigger_deg,
                               {.unit = "deg", .min = 0.0, .above_min = true, .doc = "rotation between deliveries that triggers it"});
                      f.number("trigger_m", v.trigger_m,
                               {.unit = "m", .min = 0.0, .above_min = true, .doc = "translation between deliveries that triggers it"});
                      f.integer("block_px", v.block_px, {.unit = "px", .min = 2.0, .max = 256.0, .doc = "low resolution: block size"});
                      f.check("kind", !(double_buffer && v.kind != Mode::Normal),
                              "the double_buffer strategy has no fallback; use \"kind\": \"none\" or strategy frameless");
                    },
                    {.doc = "fallback on fast motion (none when absent)"});
}

}  // namespace frameless

PipelineEntry frameless_pipeline() {
  return pipeline_entry<frameless::FramelessPipeline>(
      "frameless",
      "Frameless rendering beside double buffering on one pixel budget (Bishop et al.): each pixel computed from "
      "the newest pose and shown at the next refresh, in a randomised order without replacement (see docs/frames.md).");
}

}  // namespace latsim::pipelines
