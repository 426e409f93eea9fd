#include "frame_stages/compositor.hpp"

#include <algorithm>

#include "latsim/pipelines/pipeline.hpp"
#include "latsim/results/frame_recorder.hpp"
#include "latsim/results/figure_writer.hpp"

namespace latsim::pipelines::frame_stages {

namespace {
using Mode = WarpSpec::Mode;
// Image ids kept for rewarps_of(): far more than are on screen at once.
constexpr int64_t kRememberImages = 4096;
}  // namespace

Compositor::Compositor(RunContext& ctx, const WarpSpec& spec, des::Resource& eye_buffers)
    : ctx_(ctx),
      spec_(spec),
      planned_showings_(spec.half_rate ? 2 : 1),
      eye_buffers_(eye_buffers),
      clock_(ctx.display.timing(), spec.strips) {}

void Compositor::on_frame_complete(const JobRecord& frame) {
  if (frame.not_before > ctx_.sim.now() && !frame.skipped) {
    // Done before the retrace it is predicted for: it waits there, in its eye buffer.
    held_.push_back(Held{frame.job, *frame.last_pose, frame.not_before});
    return;
  }
  adopt(frame.job, *frame.last_pose);
}

void Compositor::release_held(des::Time retrace) {
  size_t n = 0;
  while (n < held_.size() && held_[n].not_before <= retrace) {
    adopt(held_[n].job, held_[n].pose);
    ++n;
  }
  held_.erase(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(n));
}

void Compositor::adopt(int64_t job, const tracker::PosePrediction& pose) {
  EyeImage img;
  img.pose = pose;
  for (int eye = 0; eye < ctx_.display.eyes(); ++eye) img.eye_poses.push_back(ctx_.eye_pose(img.pose.pose, eye));
  if (spec_.mode == Mode::render || (newest_ && job < *newest_)) {
    // Nothing reads it: beam racing renders its own strips, and an image
    // older than the newest (alternate frame rendering) is never warped.
    eye_buffers_.release();
    return;
  }
  const std::optional<int64_t> previous = newest_;
  images_.emplace(job, std::move(img));
  newest_ = job;
  if (previous) {
    images_.at(*previous).superseded = true;
    release_if_unused(*previous);
  }
}

void Compositor::release_if_unused(int64_t frame) {
  auto it = images_.find(frame);
  if (it == images_.end() || !it->second.superseded || it->second.readers > 0) return;
  images_.erase(it);
  eye_buffers_.release();
}

void Compositor::count_refresh(EyeImage& src, const JobRecord& warp) {
  // Counted once per refresh, at its first strip: an image that arrives
  // while a refresh is being warped strip by strip counts from the next one.
  if (clock_.slot_of(warp.deadline).strip != 0) return;
  // Every refresh showing an application frame is its first showing or a
  // re-warp: frames_shown + frames_rewarped, and a re-warp is planned
  // (frames_synthesised) or missed (frames_missed).
  const int before = src.refreshes++;
  if (before == 0) {
    ++frames_shown_;
    return;
  }
  ++frames_rewarped_;
  // At half rate every image is planned to be shown twice (a throttled
  // runtime: n times); showings beyond that are misses.
  if (before < planned_showings_) ++frames_synthesised_;
  else ctx_.app_frames.missed();
}

void Compositor::account_refresh(int64_t field) {
  // A warp that ended late makes the next one aim past the refreshes it can
  // no longer meet ("late" start): those refreshes get no warp at all.
  if (last_accounted_field_ >= 0 && field > last_accounted_field_ + 1) {
    refreshes_without_warp_ += field - last_accounted_field_ - 1;
    gap_begin_ = last_accounted_field_ + 1;
    gap_end_ = field;
  }
  last_accounted_field_ = std::max(last_accounted_field_, field);
}

bool Compositor::on_begin(JobRecord& warp) {
  if (spec_.mode == Mode::render) return true;
  if (!held_.empty()) release_held(ctx_.display.timing().field_start(clock_.slot_of(warp.deadline).field));
  if (clock_.slot_of(warp.deadline).strip == 0) account_refresh(clock_.slot_of(warp.deadline).field);
  if (!newest_) {
    if (clock_.slot_of(warp.deadline).strip == 0) ++refreshes_without_image_;
    return false;
  }
  // Once an image exists the compositor means to show a new (warped) one at
  // every refresh: the recorder counts the refreshes that show none (a warp
  // that ends late, or a synchronous warp without a new frame).
  const WarpClock::Slot slot = clock_.slot_of(warp.deadline);
  if (slot.strip == 0) ctx_.signals.image_due(ctx_.display.timing().field_start(slot.field));
  EyeImage& src = images_.at(*newest_);
  if (!spec_.asynchronous && src.refreshes > 0) {
    // Synchronous warp: no new image, no warp; the display shows the last one again.
    if (clock_.slot_of(warp.deadline).strip == 0) ctx_.app_frames.missed();
    return false;
  }
  count_refresh(src, warp);
  ++src.readers;
  warp.tag = *newest_;
  return true;
}

results::ImageRecord Compositor::warped_record(const JobRecord& warp, int64_t frame, const EyeImage* src, int eye) const {
  const tracker::PosePrediction& now_pose = *warp.last_pose;
  const des::Time now = ctx_.sim.now();
  if (spec_.mode == Mode::render) {
    // Drawn anew by the compositor: no application frame is shown.
    results::ImageRecord rec = ctx_.image_record(warp.job, eye, now_pose, warp.last_sample_at, now);
    rec.shows_app_frame = false;
    return rec;
  }
  if (!spec_.reproject_new_frames && src->refreshes == 1) {
    // Its first showing, as rendered: only frames shown again are re-projected.
    return ctx_.image_record(frame, eye, src->pose, warp.last_sample_at, now);
  }
  if (spec_.mode == Mode::positional) {
    results::ImageRecord rec = ctx_.image_record(frame, eye, now_pose, warp.last_sample_at, now);
    rec.warp = results::ImageRecord::Warp::positional;
    rec.source_pose = src->eye_poses[static_cast<size_t>(eye)];
    ctx_.draw_controller(rec, src->pose);
    return rec;
  }
  // Rotation only: the position (and the latency origin of the whole pose)
  // stays the rendered one; the orientation is the newest.
  results::ImageRecord rec = ctx_.image_record(frame, eye, src->pose, warp.last_sample_at, now);
  rec.warp = results::ImageRecord::Warp::rotation;
  rec.source_pose = src->eye_poses[static_cast<size_t>(eye)];
  rec.eye_pose.position_m = rec.source_pose.position_m;
  rec.eye_pose.orientation = ctx_.eye_pose(now_pose.pose, eye).orientation;
  rec.orientation_measured_at = now_pose.sample.measured_at;
  // What is shown: the rendered position and the warp's orientation,
  // predicted for the warp's own photon time.
  rec.predicted_for = now_pose.target;
  rec.head_pose.orientation = now_pose.pose.orientation;
  return rec;
}

void Compositor::on_complete(JobRecord& warp) {
  if (warp.skipped) return;
  ++warps_;
  const EyeImage* src = warp.tag >= 0 ? &images_.at(warp.tag) : nullptr;
  const int rewarps = src ? std::max(0, src->refreshes - 1) : 0;
  const bool late = ctx_.sim.now() > warp.deadline;
  if (late) ++warps_late_;
  for (int eye = 0; eye < ctx_.display.eyes(); ++eye) {
    results::ImageRecord rec = warped_record(warp, warp.tag, src, eye);
    rec.continues_image = clock_.slot_of(warp.deadline).strip > 0;
    const int64_t id = ctx_.images.add(rec);
    rewarps_.emplace(id, rewarps);
    // One strip: swapped in at the retrace (the next one if this warp is
    // late). Strips: written into the front buffer just ahead of the beam.
    if (clock_.strips() == 1) ctx_.display.present_at_next_retrace(eye, id);
    else ctx_.display.present_now(eye, id);
  }
  while (!rewarps_.empty() && rewarps_.begin()->first < rewarps_.rbegin()->first - kRememberImages)
    rewarps_.erase(rewarps_.begin());
  if (src) {
    --images_.at(warp.tag).readers;
    release_if_unused(warp.tag);
  }
}

int Compositor::rewarps_of(int64_t image_id) const {
  auto it = rewarps_.find(image_id);
  return it == rewarps_.end() ? -1 : it->second;
}

}  // namespace latsim::pipelines::frame_stages
