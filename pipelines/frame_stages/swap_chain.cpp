#include "frame_stages/swap_chain.hpp"

#include "latsim/pipelines/pipeline.hpp"
#include "latsim/results/frame_recorder.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "latsim/results/timeline.hpp"

namespace latsim::pipelines::frame_stages {

SwapChain::SwapChain(RunContext& ctx, des::Resource& images, bool vsync) : ctx_(ctx), images_(images), vsync_(vsync) {}

void SwapChain::on_frame_complete(const JobRecord& frame) {
  Done d{frame.job, {}, ctx_.sim.now()};
  for (int eye = 0; eye < ctx_.display.eyes(); ++eye) {
    const results::ImageRecord rec = ctx_.image_record(frame.job, eye, *frame.last_pose, frame.last_sample_at, d.completed);
    d.ids.push_back(ctx_.images.add(rec));
  }
  // Frames are presented in the order they were issued.
  early_.emplace(frame.job, std::move(d));
  for (auto it = early_.find(next_frame_); it != early_.end(); it = early_.find(next_frame_)) {
    ++next_frame_;
    if (vsync_) queue_.push_back(std::move(it->second));
    else show(it->second);
    early_.erase(it);
  }
  if (vsync_ && ctx_.timeline) ctx_.timeline->add_counter("queue_depth", ctx_.sim.now(), static_cast<double>(queue_.size()));
}

void SwapChain::on_retrace(int64_t) {
  if (!vsync_) return;
  // Once a frame is on screen the application means to show a new one at
  // every refresh: the recorder counts the refreshes that show none.
  if (on_screen_) ctx_.recorder.image_due(ctx_.sim.now());
  if (queue_.empty()) {
    if (on_screen_) ctx_.app_frames.missed();
    return;
  }
  const Done d = std::move(queue_.front());
  queue_.pop_front();
  if (ctx_.timeline) ctx_.timeline->add_counter("queue_depth", ctx_.sim.now(), static_cast<double>(queue_.size()));
  if (ctx_.timeline) ctx_.timeline->add("QUEUED", d.frame, -1, "swapchain", d.completed, ctx_.sim.now());
  show(d);
}

void SwapChain::show(const Done& d) {
  for (int eye = 0; eye < ctx_.display.eyes(); ++eye) ctx_.display.present_now(eye, d.ids[static_cast<size_t>(eye)]);
  ctx_.app_frames.flipped(d.frame, ctx_.sim.now());
  // The image that was on screen is free to be drawn into again.
  if (on_screen_) images_.release();
  on_screen_ = true;
  ++frames_shown_;
}

}  // namespace latsim::pipelines::frame_stages
