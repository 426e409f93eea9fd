#include "passthrough/passthrough_pipeline.hpp"

#include <algorithm>

#include "latsim/results/figure_writer.hpp"
#include "latsim/results/timeline.hpp"

namespace latsim::pipelines::passthrough {

namespace {
// Camera frames kept after a newer one is processed: enough for any composition still using one.
constexpr int64_t kKeepFrames = 64;
}  // namespace

PassthroughPipeline::PassthroughPipeline(const Params& params) : spec_(params.spec) {}
PassthroughPipeline::~PassthroughPipeline() = default;

des::Time PassthroughPipeline::isp_pixel_time(const PassthroughSpec& spec) {
  if (spec.isp.pixel_rate_mpx_s <= 0.0) return des::Time::zero();
  const double pixels = static_cast<double>(spec.camera.width_px * spec.camera.height_px);
  return des::Time::from_seconds(pixels / (spec.isp.pixel_rate_mpx_s * 1e6));
}

void PassthroughPipeline::start(RunContext& ctx) {
  ctx_ = &ctx;
  ctx.signals.shows_images();
  const CameraSpec& cam = spec_.camera;
  if (cam.sync == CameraSpec::Sync::display) {
    camera_ = std::make_unique<CameraTiming>(cam, ctx.display.timing());
  } else {
    const des::Clock& clock = ctx.clock("passthrough_camera", "/pipeline/camera/phase_ms", cam.frame_period, cam.clock);
    camera_ = std::make_unique<CameraTiming>(cam, clock.schedule());
  }
  const display::RasterTiming& timing = ctx.display.timing();
  const measurement::ShownTrace point(spec_.point, timing.params().width_px, timing.lines_per_field());
  point_line_ = point.line();
  point_x_ = point.column();
  point_row_ = camera_->row_at(spec_.point.y);
  kind_readout_ = ctx.sim.kind("passthrough.readout");
  kind_isp_ = ctx.sim.kind("passthrough.isp");
  kind_compose_ = ctx.sim.kind("passthrough.compositor");
  kind_composed_ = ctx.sim.kind("passthrough.compositor_end");
  if (spec_.rig) {
    const RigSpec& r = *spec_.rig;
    object_ = tracker::make_motion(r.object);
    const glm::dquat reference = object_->pose_at(des::Time::zero()).orientation;
    object_signal_ = std::make_unique<measurement::ObjectSignal>(
        [this, reference, axis = r.rig.axis](des::Time t) {
          return measurement::twist_deg(reference, object_->pose_at(t).orientation, axis);
        });
    rig_camera_ = ctx.clock("passthrough_rig", "/pipeline/rig/phase_ms", r.rig.frame_period, r.rig.clock).schedule();
  }
  ctx.display.on_retrace([this](int64_t field, des::Time) {
    retraced(field);
    if (spec_.compositor.start != CompositorSpec::Start::before_retrace) return;
    const des::Time next = ctx_->display.timing().field_start(field + 1) - spec_.compositor.lead;
    if (next >= ctx_->sim.now() && next <= ctx_->duration)
      ctx_->sim.at(next, kind_compose_, [this, field] { compose_for(field + 1); });
  });
  const des::Time first = camera_->readout_end(0);
  if (first <= ctx.duration) ctx.sim.at(first, kind_readout_, [this] { read_out(0); });
}

void PassthroughPipeline::read_out(int64_t k) {
  const des::Time now = ctx_->sim.now();
  ++frames_read_;
  const des::Time next = camera_->readout_end(k + 1);
  if (next <= ctx_->duration) ctx_->sim.at(next, kind_readout_, [this, k] { read_out(k + 1); });
  // The image signal processor takes frames in order, one at a time.
  const IspSpec& isp = spec_.isp;
  const des::Time pixels = isp_pixel_time(spec_);
  des::Time start, end;
  if (isp.line_streamed) {
    // Rows are processed as they are read: the pixel engine cannot finish
    // before the last row arrives; the fixed time is its pipeline's depth.
    start = std::max(camera_->readout_start(k), isp_free_);
    end = std::max(start + pixels, now) + isp.fixed;
    isp_free_ = end - isp.fixed;
  } else {
    start = std::max(now, isp_free_);
    end = start + isp.fixed + pixels;
    isp_free_ = end;
  }
  frames_[k].readout_end = now;
  if (ctx_->timeline) {
    ctx_->timeline->add("CAMERA", k, -1, "camera", camera_->frame_start(k), now);
    ctx_->timeline->add("ISP", k, -1, "isp", start, end);
  }
  ctx_->sim.at(end, kind_isp_, [this, k] { processed(k); });
}

void PassthroughPipeline::processed(int64_t k) {
  frames_[k].isp_end = ctx_->sim.now();
  // A processed frame that a newer one replaces before any composition took it is dropped.
  if (newest_processed_ && !frames_.at(*newest_processed_).picked) ++frames_dropped_;
  newest_processed_ = k;
  while (!frames_.empty() && frames_.begin()->first < k - kKeepFrames) frames_.erase(frames_.begin());
  if (spec_.compositor.start == CompositorSpec::Start::on_frame) compose_for(-1);
}

void PassthroughPipeline::compose_for(int64_t field) {
  // The compositor waits for the GPU it runs on.
  const des::Time now = ctx_->sim.now();
  if (gpu_free_ > now) {
    ctx_->sim.at(gpu_free_, kind_compose_, [this, field] { compose_now(field); });
    return;
  }
  compose_now(field);
}

void PassthroughPipeline::compose_now(int64_t field) {
  const des::Time now = ctx_->sim.now();
  // On a new frame: for the first refresh whose retrace follows the composition.
  if (field < 0) field = ctx_->display.timing().field_at_or_after(now + composition_time());
  if (!newest_processed_) {
    ++refreshes_without_image_;
    return;
  }
  const std::optional<tracker::PosePrediction> pose = ctx_->host.pose_for(now, ctx_->frame_photon_time(field));
  if (!pose) return;  // no head pose yet
  const int64_t k = *newest_processed_;
  Frame& f = frames_.at(k);
  if (f.picked) ++frames_repeated_;
  f.picked = true;
  gpu_free_ = now + composition_time();
  ctx_->sim.at(gpu_free_, kind_composed_, [this, field, k, p = *pose, now] { composed(field, k, p, now); });
}

void PassthroughPipeline::composed(int64_t field, int64_t k, const tracker::PosePrediction& pose, des::Time start) {
  const des::Time now = ctx_->sim.now();
  if (ctx_->display.timing().field_at_or_after(now) > field) ++warps_late_;
  // The camera image re-projected to each eye's viewpoint at the newest
  // head pose, predicted for the refresh it is meant for.
  for (int eye = 0; eye < ctx_->display.eyes(); ++eye) {
    const int64_t id = ctx_->images.add(ctx_->image_record(k, eye, pose, start, now));
    if (eye == 0) compositions_[id] = Composition{k, start, now};
    ctx_->display.present_at_next_retrace(eye, id);
  }
  if (ctx_->timeline) ctx_->timeline->add("REPROJECT", k, -1, "gpu", start, now);
}

void PassthroughPipeline::retraced(int64_t field) {
  auto it = compositions_.find(ctx_->display.front(0));
  if (it == compositions_.end()) return;  // nothing composed shown yet
  const Composition c = it->second;
  compositions_.erase(compositions_.begin(), it);  // older images are never shown again
  const des::Time photon = ctx_->photon_time(field, point_line_, point_x_);
  auto f = frames_.find(c.frame);
  if (f != frames_.end() && !f->second.shown) first_shown(f->second, c, field, photon);
  light_point(field, c, photon);
}

void PassthroughPipeline::first_shown(Frame& f, const Composition& c, int64_t field, des::Time photon) {
  f.shown = true;
  ++frames_shown_;
  // Each stage from the camera row's exposure middle to the photons at the
  // point; they add up to photon_to_photon_ms of the first refresh showing it.
  const des::Time retrace = ctx_->display.timing().field_start(field);
  results::FigureWriter& r = ctx_->figures;
  r.add("camera_ms", (f.readout_end - camera_->exposure_middle(c.frame, point_row_)).to_ms());
  r.add("isp_ms", (f.isp_end - f.readout_end).to_ms());
  r.add("reprojection_queue_ms", (c.start - f.isp_end).to_ms());
  r.add("reprojection_ms", (c.end - c.start).to_ms());
  r.add("display_wait_ms", (retrace - c.end).to_ms());
  r.add("scanout_ms", (photon - retrace).to_ms());
}

void PassthroughPipeline::light_point(int64_t field, const Composition& c, des::Time photon) {
  ctx_->figures.add("photon_to_photon_ms", (photon - camera_->exposure_middle(c.frame, point_row_)).to_ms());
  if (!object_signal_) return;
  // What the point shows of the real object: its angle as the camera's row
  // saw it over its exposure, lit over the pixel's lit interval.
  const des::Time open = camera_->row_open(c.frame, point_row_);
  const double angle = object_signal_->seen(open, open + spec_.camera.exposure).value_or(0.0);
  const des::Time written = ctx_->display.timing().pixel_time(field, point_line_, point_x_);
  const display::LitInterval lit = ctx_->display.persistence().configured()
                                       ? ctx_->display.persistence().lit(field, written)
                                       : display::LitInterval{written, des::Time::zero()};
  const double from = lit_.empty() ? angle : lit_.back().angle_deg;
  lit_.push_back(measurement::LitAngle{lit.on, lit.on + lit.duration, angle, written, from});
}

void PassthroughPipeline::finish(RunContext& ctx) {
  results::FigureWriter& r = ctx.figures;
  r.set("camera_frames", frames_read_);
  r.set("camera_frames_shown", frames_shown_);
  r.set("camera_frames_dropped", frames_dropped_);
  r.set("camera_frames_repeated", frames_repeated_);
  r.set("refreshes_without_image", refreshes_without_image_);
  r.set("warps_late", warps_late_);
  if (spec_.rig) film_object(ctx);
  r.use_headline("passthrough");
}

std::vector<EventRate> PassthroughPipeline::event_rates(const sections::SharedParams& shared) const {
  const double refresh_per_s = 1.0 / shared.display.raster.field_period.to_seconds();
  const double frames_per_s = spec_.camera.sync == CameraSpec::Sync::display
                                  ? refresh_per_s / spec_.camera.refreshes_per_frame
                                  : 1.0 / spec_.camera.frame_period.to_seconds();
  // Per camera frame: its readout, the ISP's end, a composition's start and
  // end (on_frame); per refresh a composition's start and end (before_retrace).
  const bool per_refresh = spec_.compositor.start == CompositorSpec::Start::before_retrace;
  const double per_s = 2.0 * frames_per_s + 2.0 * (per_refresh ? refresh_per_s : frames_per_s);
  return {{"/pipeline/camera", "passthrough", per_s}};
}

}  // namespace latsim::pipelines::passthrough
