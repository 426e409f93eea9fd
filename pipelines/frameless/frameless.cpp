// Frameless rendering and double buffering on one pixel budget (SPEC section 6).
//
// Both strategies spend the same number of pixel computations per second;
// pixel k of the run's computation stream occupies [at(k), at(k+1)) on an
// exact periodic schedule. Frameless writes each pixel at once, from the
// newest pose when its computation starts, and the display latches what has
// been written at every retrace. Double buffering spends width x height x eyes
// consecutive pixels on one image from one pose and swaps it in at the next
// retrace. Pixels are simulated exactly but handled in chunks, one event per
// chunk, so the event count stays far below one per pixel.
#include "frameless/frameless_order.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <optional>

#include "latsim/des/process.hpp"
#include "latsim/pipelines/frame_capture.hpp"
#include "latsim/pipelines/latency_recorder.hpp"
#include "latsim/pipelines/timeline.hpp"
#include "latsim/renderer/camera.hpp"

namespace latsim::pipelines {

FramelessOrder::FramelessOrder(int32_t pixel_count, des::RandomStream stream) {
  if (pixel_count < 1) throw std::invalid_argument("frameless order: needs at least one pixel");
  table_.resize(static_cast<size_t>(pixel_count));
  for (int32_t i = 0; i < pixel_count; ++i) table_[static_cast<size_t>(i)] = i;
  stream.shuffle(table_);
}

namespace {

constexpr double kPi = 3.14159265358979323846;

/// What one buffer pixel holds: the sample its colour was computed from (a
/// slot in the pipeline's sample list; -1 = never computed), the pixel,
/// within its eye, whose ray gave the colour (itself, or its block's sample
/// pixel at reduced resolution), and the field it was expected to be shown
/// in first when it was computed (its pose is predicted to its photon time
/// there).
struct PixelState {
  int64_t slot = -1;
  int32_t source = 0;
  int64_t field = 0;
};

/// What the pipeline does with its next unit of pixel budget.
enum class Mode { Normal, LowResolution, DoubleBufferFallback };

/// Both strategies of SPEC section 6 on one pixel budget; frameless also
/// supplies its per-pixel poses to a frame capture.
class FramelessPipeline final : public Pipeline, public display::ScanoutListener, public PixelSource {
 public:
  /// The /pipeline keys, and what they fix before the run.
  struct Params {
    bool double_buffer = false;
    std::optional<double> pixels_per_s;
    double full_images_per_s = 5.0;
    int64_t chunk_pixels = 2048;
    int64_t sample_pixels = 1024;
    double registration_depth_m = 2.0;
    /// What happens when the head moves fast (nothing when absent).
    struct Fallback {
      Mode kind = Mode::LowResolution;
      double trigger_deg = 20.0;
      double trigger_m = 0.5;
      int block_px = 4;
    };
    std::optional<Fallback> fallback;
    int64_t budget_px_s = 1;  ///< whole pixels per second (an exact rational period)
    des::ClockSettings loop;  ///< the computation's own clock (phase over one full image)
  };

  explicit FramelessPipeline(const Params& p)
      : double_buffer_(p.double_buffer),
        budget_px_s_(p.budget_px_s),
        chunk_px_(p.chunk_pixels),
        depth_m_(p.registration_depth_m),
        fallback_(p.fallback ? p.fallback->kind : Mode::Normal),
        trigger_deg_(p.fallback ? p.fallback->trigger_deg : 20.0),
        trigger_m_(p.fallback ? p.fallback->trigger_m : 0.5),
        block_px_(p.fallback ? p.fallback->block_px : 4),
        sample_pixels_(p.sample_pixels),
        loop_(p.loop) {}

  void start(RunContext& ctx) override {
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

  void finish(RunContext& ctx) override {
    if (ctx.frames) ctx.frames->set_pixel_source(nullptr);
    const double cycle_ms = static_cast<double>(pixels_) / static_cast<double>(budget_px_s_) * 1e3;
    LatencyRecorder& r = ctx.recorder;
    r.set("frameless.strategy", std::string(double_buffer_ ? "double_buffer" : "frameless"));
    r.set("frameless.pixels_per_s", budget_px_s_);
    r.set("frameless.pixels_per_cycle", int64_t{pixels_});
    r.set("frameless.cycle_ms", cycle_ms);
    r.set("frameless.pixels_computed", computed_units_);
    r.set("frameless.images_rendered", images_);
    r.set("frameless.fallbacks", fallbacks_);
    r.set("frameless.sampled_pixels", int64_t{sampled_count_});
    r.set("frameless.chunk_pixels", chunk_px_);
    // Frameless shows no whole images (no frame_rate_hz): it completes update cycles.
    r.set("frameless.cycle_rate_hz", 1e3 / cycle_ms);
  }

  void on_scanout(const display::ScanoutSpan& span) override {
    const ImageRecord* image = double_buffer_ ? ctx_->recorder.image(span.image_id) : nullptr;
    if (double_buffer_ && image == nullptr) return;
    for (int line = span.line; line < span.line_end; ++line) sample_line(span, line, image);
  }

  // Ages (and registration) of the sampled pixels of one line of a span.
  void sample_line(const display::ScanoutSpan& span, int line, const ImageRecord* image) {
    const int row = ctx_->display.timing().row_of(span.field, line);
    const auto& xs = sampled_[static_cast<size_t>(span.eye) * static_cast<size_t>(height_) + static_cast<size_t>(row)];
    for (auto it = std::lower_bound(xs.begin(), xs.end(), span.x_begin); it != xs.end() && *it < span.x_end; ++it) {
      const des::Time photon = ctx_->display.timing().pixel_time(span.field, line, *it);
      if (image != nullptr) {
        ctx_->recorder.pixel_age(image->sample, photon);
        continue;
      }
      const PixelState& st = visible_[pixel_id(span.eye, *it, row)];
      if (st.slot < 0) continue;
      const auto [first_field, pose] = pixel_pose(st, *it, row);
      ctx_->recorder.pixel_lit(pose.sample, photon);
      registration(span.eye, *it, row, st, pose.pose, photon);
      // Each pixel's own prediction, judged once: where it was first shown.
      if (ctx_->host.predicts() && span.eye == 0 && span.field == first_field)
        ctx_->recorder.add_prediction_error(pose, true, true);
    }
  }

  void shown_pixels(int eye, int row, int x_begin, std::span<ShownPixel> out) const override {
    for (size_t i = 0; i < out.size(); ++i) {
      const int x = x_begin + static_cast<int>(i);
      const PixelState& st = visible_[pixel_id(eye, x, row)];
      ShownPixel& p = out[i];
      p.lit = st.slot >= 0;
      if (!p.lit) continue;
      const tracker::PosePrediction pose = pixel_pose(st, x, row).second;
      p.eye_pose = ctx_->eye_pose(pose.pose, eye);
      p.measured_at = pose.sample.measured_at;
      p.source_x = st.source % width_;
      p.source_y = st.source / width_;
    }
  }

 private:
  void size_to_display(RunContext& ctx) {
    width_ = ctx.display.timing().params().width_px;
    height_ = ctx.display.timing().params().height_px;
    eyes_ = ctx.display.eyes();
    pixels_ = static_cast<int32_t>(int64_t{width_} * height_ * eyes_);
    sampled_count_ = static_cast<int32_t>(std::min<int64_t>(sample_pixels_, pixels_));
    const double hfov_deg = ctx.display_params.hfov_deg;
    camera_.emplace(hfov_deg, width_, height_);
  }

  size_t pixel_id(int eye, int x, int row) const {
    return (static_cast<size_t>(eye) * static_cast<size_t>(height_) + static_cast<size_t>(row)) *
               static_cast<size_t>(width_) + static_cast<size_t>(x);
  }

  // A fixed random subset of pixels, the same for both strategies, where
  // ages and registration are sampled at every refresh.
  void pick_sampled_pixels(des::RandomStream stream) {
    sampled_.assign(static_cast<size_t>(eyes_) * static_cast<size_t>(height_), {});
    const FramelessOrder pick(pixels_, std::move(stream));
    for (int32_t i = 0; i < sampled_count_; ++i) {
      const int32_t p = pick.pixel_of(i);
      sampled_[static_cast<size_t>(p / width_)].push_back(p % width_);
    }
    for (auto& xs : sampled_) std::sort(xs.begin(), xs.end());
  }

  void make_blocks(des::RandomStream stream) {
    blocks_x_ = (width_ + block_px_ - 1) / block_px_;
    blocks_y_ = (height_ + block_px_ - 1) / block_px_;
    block_order_.emplace(blocks_x_ * blocks_y_ * eyes_, std::move(stream));
  }

  const tracker::PredictionBasis& basis_of(int64_t slot) const {
    return samples_[static_cast<size_t>(slot - slot_base_)];
  }

  int64_t slot_for(const tracker::TrackerSample& s) {
    // Pixels are computed in time order, so the samples they use never go
    // back; a pixel may be shown for longer than the host remembers its
    // sample, so the slot keeps what the host knew then.
    if (samples_.empty() || samples_.back().sample.index != s.index) samples_.push_back(ctx_->host.basis_of(s));
    return slot_base_ + static_cast<int64_t>(samples_.size()) - 1;
  }

  /// The field in which a pixel is first shown and the pose it was computed
  /// from, predicted to its own photon time there (frameless computes pixel
  /// by pixel, so each has its own horizon). Interlaced, a row missing from
  /// the field it was latched for is first lit in the next one.
  std::pair<int64_t, tracker::PosePrediction> pixel_pose(const PixelState& st, int x, int row) const {
    const display::RasterTiming& t = ctx_->display.timing();
    int64_t field = st.field;
    int line = t.line_of_row(field, row);
    if (line < 0) line = t.line_of_row(++field, row);
    return {field, basis_of(st.slot).for_photon_time(t.pixel_time(field, line, x))};
  }

  /// The field whose retrace first latches a pixel computed in unit k: the
  /// first retrace at or after the unit ends (a double-buffering fallback:
  /// after its whole image).
  int64_t latch_field(int64_t k) const {
    const int64_t done = mode_ == Mode::DoubleBufferFallback ? fallback_end_unit_ : k + 1;
    return ctx_->display.timing().field_at_or_after(schedule_.at(done));
  }

  // ---- frameless: the pixel stream -------------------------------------

  /// Computes the pixel stream a chunk at a time (retraces also catch it up).
  des::Process pixel_stream() {
    for (;;) {
      const des::Time t = schedule_.at(next_unit_ + chunk_px_);
      if (t >= ctx_->duration) co_return;
      co_await ctx_->sim.until(t);
      advance_to(ctx_->sim.now());
    }
  }

  /// Computes every pixel whose computation ends at or before t.
  void advance_to(des::Time t) {
    const int64_t end = schedule_.index_at_or_before(t);
    while (next_unit_ < end) {
      while (!triggers_.empty() && triggers_.front() <= next_unit_) {
        triggers_.pop_front();
        begin_fallback(next_unit_);
      }
      compute(next_unit_, end);
      ++next_unit_;
    }
  }

  /// The newest sample when unit k starts; a cache holds it for the units
  /// after k that still see it (found by bisection: newest_at only moves on).
  std::optional<tracker::TrackerSample> newest_for(int64_t k, int64_t end) {
    if (k <= cached_until_) return cached_;
    cached_ = ctx_->host.newest_at(schedule_.at(k));
    const int64_t index = cached_ ? cached_->index : -1;
    int64_t lo = k, hi = end - 1;
    while (lo < hi) {
      const int64_t mid = lo + (hi - lo + 1) / 2;
      const auto s = ctx_->host.newest_at(schedule_.at(mid));
      if ((s ? s->index : -1) == index) lo = mid;
      else hi = mid - 1;
    }
    cached_until_ = lo;
    return cached_;
  }

  void compute(int64_t k, int64_t end) {
    ++computed_units_;
    if (mode_ == Mode::LowResolution) {
      const auto s = newest_for(k, end);
      const int32_t b = block_order_->pixel_of(block_cursor_++);
      if (block_cursor_ == block_order_->pixel_count()) mode_ = Mode::Normal;
      if (s) write_block(b, slot_for(*s), latch_field(k));
      return;
    }
    const int32_t p = order_->pixel_of(cursor_++);
    if (cursor_ % pixels_ == 0) prune_samples();
    if (mode_ == Mode::DoubleBufferFallback) {
      // One image from one pose, held back from the display until complete.
      write(p, fallback_slot_, p % (width_ * height_), latch_field(k));
      if (--fallback_left_ == 0) mode_ = Mode::Normal;
      return;
    }
    if (const auto s = newest_for(k, end)) write(p, slot_for(*s), p % (width_ * height_), latch_field(k));
  }

  void write(int32_t p, int64_t slot, int32_t source, int64_t field) {
    computed_[static_cast<size_t>(p)] = PixelState{slot, source, field};
    if (stamp_[static_cast<size_t>(p)] != generation_) {
      stamp_[static_cast<size_t>(p)] = generation_;
      dirty_.push_back(p);
    }
  }

  void write_block(int32_t b, int64_t slot, int64_t field) {
    const int per_eye = blocks_x_ * blocks_y_;
    const int eye = b / per_eye, bx = (b % per_eye) % blocks_x_, by = (b % per_eye) / blocks_x_;
    const int x0 = bx * block_px_, y0 = by * block_px_;
    const int x1 = std::min(width_, x0 + block_px_), y1 = std::min(height_, y0 + block_px_);
    // The block's colour is the ray through its middle pixel.
    const int32_t source = ((y0 + y1) / 2) * width_ + (x0 + x1) / 2;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) write(static_cast<int32_t>(pixel_id(eye, x, y)), slot, source, field);
  }

  void delivered(const tracker::TrackerSample& s, des::Time t) {
    if (last_delivered_) {
      const double angle_deg = tracker::angle_between(last_delivered_->orientation, s.pose.orientation) * 180.0 / kPi;
      const double moved_m = glm::length(s.pose.position_m - last_delivered_->position_m);
      // Units that start at or after the delivery fall back; earlier ones are unchanged.
      if (angle_deg > trigger_deg_ || moved_m > trigger_m_) triggers_.push_back(schedule_.index_at_or_after(t));
    }
    last_delivered_ = s.pose;
  }

  void begin_fallback(int64_t k) {
    ++fallbacks_;
    ctx_->recorder.count("frameless_fallbacks");
    if (fallback_ == Mode::LowResolution) {
      mode_ = Mode::LowResolution;
      block_cursor_ = 0;
      return;
    }
    const auto s = ctx_->host.newest_at(schedule_.at(k));
    if (!s) return;
    mode_ = Mode::DoubleBufferFallback;
    fallback_slot_ = slot_for(*s);
    fallback_left_ = pixels_;
    fallback_end_unit_ = k + pixels_;
  }

  // Drops samples no pixel refers to any more (checked once per cycle).
  void prune_samples() {
    int64_t oldest = slot_base_ + static_cast<int64_t>(samples_.size());
    for (const auto* buffer : {&computed_, &visible_})
      for (const PixelState& st : *buffer)
        if (st.slot >= 0) oldest = std::min(oldest, st.slot);
    if (mode_ == Mode::DoubleBufferFallback) oldest = std::min(oldest, fallback_slot_);
    // Keep the newest sample: slot_for compares against it.
    oldest = std::min(oldest, slot_base_ + static_cast<int64_t>(samples_.size()) - 1);
    while (slot_base_ < oldest) {
      samples_.pop_front();
      ++slot_base_;
    }
  }

  // ---- both strategies at each refresh ---------------------------------

  void retrace(int64_t, des::Time now) {
    if (double_buffer_) {
      const int64_t front = ctx_->display.front(0);
      ctx_->recorder.add("updated_fraction", front != last_front_ ? 1.0 : 0.0);
      last_front_ = front;
      return;
    }
    advance_to(now);
    // A double-buffering fallback shows nothing new until its image is complete.
    if (mode_ == Mode::DoubleBufferFallback) {
      ctx_->recorder.add("updated_fraction", 0.0);
      return;
    }
    for (int32_t p : dirty_) visible_[static_cast<size_t>(p)] = computed_[static_cast<size_t>(p)];
    ctx_->recorder.add("updated_fraction", static_cast<double>(dirty_.size()) / static_cast<double>(pixels_));
    dirty_.clear();
    ++generation_;
  }

  // ---- double buffering at the same budget -----------------------------

  /// Image after image, each from the newest pose when it starts (none yet:
  /// it renders nothing), presented when its pixels are spent.
  des::Process images() {
    // Image 0 begins with the first pixel of the budget, at the clock's phase.
    if (schedule_.at(0) > ctx_->sim.now()) co_await ctx_->sim.until(schedule_.at(0));
    for (int64_t image = 0;; ++image) {
      const des::Time end = schedule_.at((image + 1) * pixels_);
      // Shown from the first retrace after its last pixel is spent.
      const auto pose = ctx_->host.pose_for(ctx_->sim.now(), ctx_->photon_time_after(end));
      if (end >= ctx_->duration) co_return;
      co_await ctx_->sim.until(end);
      if (!pose) continue;
      const des::Time start = schedule_.at(image * pixels_), now = ctx_->sim.now();
      for (int eye = 0; eye < eyes_; ++eye) {
        ImageRecord rec = ctx_->image_record(image, eye, *pose, start, now);
        ctx_->display.present_at_next_retrace(eye, ctx_->recorder.register_image(rec));
      }
      ++images_;
      computed_units_ += pixels_;
      if (ctx_->timeline) ctx_->timeline->add("RENDER", image, -1, "renderer", start, now);
    }
  }

  void registration(int eye, int x, int row, const PixelState& st, const tracker::Pose& head, des::Time photon) {
    const tracker::Pose drawn = ctx_->eye_pose(head, eye);
    // The pixel shows the surface point its source ray met, taken at a fixed
    // depth, drawn along the pixel's own direction.
    const int sx = st.source % width_, sy = st.source / width_;
    const glm::dvec3 point = drawn.position_m + depth_m_ * (drawn.orientation * camera_->head_direction(sx + 0.5, sy + 0.5));
    ctx_->recorder.registration(eye, point, camera_->head_direction(x + 0.5, row + 0.5), photon);
  }

  RunContext* ctx_ = nullptr;
  bool double_buffer_ = false;
  int64_t budget_px_s_ = 1;
  int64_t chunk_px_ = 2048;
  double depth_m_ = 2.0;
  Mode fallback_ = Mode::Normal;
  double trigger_deg_ = 20.0, trigger_m_ = 0.5;
  int block_px_ = 4;
  int64_t sample_pixels_ = 1024;
  des::ClockSettings loop_;
  int width_ = 0, height_ = 0, eyes_ = 1;
  int32_t pixels_ = 0;
  int32_t sampled_count_ = 0;
  std::optional<renderer::Camera> camera_;
  des::PeriodicSchedule schedule_;
  std::vector<std::vector<int>> sampled_;  ///< per (eye, row): sampled columns, sorted

  // Frameless state.
  std::optional<FramelessOrder> order_;
  std::optional<FramelessOrder> block_order_;
  int blocks_x_ = 0, blocks_y_ = 0;
  std::vector<PixelState> computed_;  ///< what has been written
  std::vector<PixelState> visible_;   ///< what the display shows (latched at retrace)
  std::vector<int64_t> stamp_;        ///< refresh generation a pixel was last written in
  std::vector<int32_t> dirty_;        ///< pixels written since the last latch
  int64_t generation_ = 0;
  std::deque<tracker::PredictionBasis> samples_;
  int64_t slot_base_ = 0;
  int64_t next_unit_ = 0;   ///< next unit of pixel budget to compute
  int64_t cursor_ = 0;      ///< updates taken from the permutation table
  int32_t block_cursor_ = 0;
  Mode mode_ = Mode::Normal;
  int64_t fallback_slot_ = -1;
  int32_t fallback_left_ = 0;
  int64_t fallback_end_unit_ = 0;  ///< the unit after the fallback image's last pixel
  std::deque<int64_t> triggers_;
  std::optional<tracker::Pose> last_delivered_;
  std::optional<tracker::TrackerSample> cached_;
  int64_t cached_until_ = -1;

  // Double-buffering state.
  int64_t last_front_ = -1;

  int64_t computed_units_ = 0;
  int64_t images_ = 0;
  int64_t fallbacks_ = 0;
};

void bind(scenario::Section& s, FramelessPipeline::Params& p, const params::SharedParams& shared) {
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
  params::clock(s, "loop_", p.loop, "pixel computation (the first pixel's start)");
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

}  // namespace

PipelineEntry frameless_pipeline() {
  return pipeline_entry<FramelessPipeline>(
      "frameless",
      "Frameless rendering beside double buffering on one pixel budget (Bishop et al.): each pixel computed from "
      "the newest pose and shown at the next refresh, in a randomised order without replacement (see docs/frames.md).");
}

}  // namespace latsim::pipelines
