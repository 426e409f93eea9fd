// The frameless pixel update process: pixel order and stream, fallbacks, retrace latch, double buffering's images.
#include "frameless/frameless_pipeline.hpp"

#include <algorithm>
#include <stdexcept>

#include "latsim/results/latency_recorder.hpp"
#include "latsim/results/timeline.hpp"
#include "latsim/units/units.hpp"

namespace latsim::pipelines {

FramelessOrder::FramelessOrder(int32_t pixel_count, des::RandomStream stream) {
  if (pixel_count < 1) throw std::invalid_argument("frameless order: needs at least one pixel");
  table_.resize(static_cast<size_t>(pixel_count));
  for (int32_t i = 0; i < pixel_count; ++i) table_[static_cast<size_t>(i)] = i;
  stream.shuffle(table_);
}

namespace frameless {

namespace {


}  // namespace

int64_t FramelessPipeline::slot_for(const tracker::TrackerSample& s) {
  // Pixels are computed in time order, so the samples they use never go
  // back; a pixel may be shown for longer than the host remembers its
  // sample, so the slot keeps what the host knew then.
  if (samples_.empty() || samples_.back().sample.index != s.index) samples_.push_back(ctx_->host.basis_of(s));
  return slot_base_ + static_cast<int64_t>(samples_.size()) - 1;
}

int64_t FramelessPipeline::latch_field(int64_t k) const {
  const int64_t done = mode_ == Mode::DoubleBufferFallback ? fallback_end_unit_ : k + 1;
  return ctx_->display.timing().field_at_or_after(schedule_.at(done));
}

// ---- frameless: the pixel stream -------------------------------------

des::Process FramelessPipeline::pixel_stream() {
  for (;;) {
    const des::Time t = schedule_.at(next_unit_ + chunk_px_);
    if (t >= ctx_->duration) co_return;
    co_await ctx_->sim.until(t);
    advance_to(ctx_->sim.now());
  }
}

void FramelessPipeline::advance_to(des::Time t) {
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

std::optional<tracker::TrackerSample> FramelessPipeline::newest_for(int64_t k, int64_t end) {
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

void FramelessPipeline::compute(int64_t k, int64_t end) {
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

void FramelessPipeline::write(int32_t p, int64_t slot, int32_t source, int64_t field) {
  computed_[static_cast<size_t>(p)] = PixelState{slot, source, field};
  if (stamp_[static_cast<size_t>(p)] != generation_) {
    stamp_[static_cast<size_t>(p)] = generation_;
    dirty_.push_back(p);
  }
}

void FramelessPipeline::write_block(int32_t b, int64_t slot, int64_t field) {
  const int per_eye = blocks_x_ * blocks_y_;
  const int eye = b / per_eye, bx = (b % per_eye) % blocks_x_, by = (b % per_eye) / blocks_x_;
  const int x0 = bx * block_px_, y0 = by * block_px_;
  const int x1 = std::min(width_, x0 + block_px_), y1 = std::min(height_, y0 + block_px_);
  // The block's colour is the ray through its middle pixel.
  const int32_t source = ((y0 + y1) / 2) * width_ + (x0 + x1) / 2;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) write(static_cast<int32_t>(pixel_id(eye, x, y)), slot, source, field);
}

void FramelessPipeline::delivered(const tracker::TrackerSample& s, des::Time t) {
  if (last_delivered_) {
    const double angle_deg = units::rad_to_deg(tracker::angle_between(last_delivered_->orientation, s.pose.orientation));
    const double moved_m = glm::length(s.pose.position_m - last_delivered_->position_m);
    // Units that start at or after the delivery fall back; earlier ones are unchanged.
    if (angle_deg > trigger_deg_ || moved_m > trigger_m_) triggers_.push_back(schedule_.index_at_or_after(t));
  }
  last_delivered_ = s.pose;
}

void FramelessPipeline::begin_fallback(int64_t k) {
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

void FramelessPipeline::prune_samples() {
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

void FramelessPipeline::retrace(int64_t, des::Time now) {
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

des::Process FramelessPipeline::images() {
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
      results::ImageRecord rec = ctx_->image_record(image, eye, *pose, start, now);
      ctx_->display.present_at_next_retrace(eye, ctx_->images.add(rec));
    }
    ++images_;
    computed_units_ += pixels_;
    if (ctx_->timeline) ctx_->timeline->add("RENDER", image, -1, "renderer", start, now);
  }
}

}  // namespace frameless

}  // namespace latsim::pipelines
