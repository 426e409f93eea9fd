#include "present_replay/present_replay_pipeline.hpp"

#include <algorithm>

#include "latsim/results/frame_recorder.hpp"
#include "latsim/results/image_book.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "latsim/results/timeline.hpp"

namespace latsim::pipelines::present_replay {

void PresentReplayPipeline::start(RunContext& ctx) {
  ctx_ = &ctx;
  kind_gpu_ = ctx.sim.kind("present_replay.gpu");
  ctx.recorder.expects_images();
  const results::PresentFacts facts{.sync_interval = p_.path.show == PresentPathSpec::Show::queued ? p_.path.sync_interval : 0,
                                    .allows_tearing = p_.path.show == PresentPathSpec::Show::immediate,
                                    .shown = true,
                                    .present_mode = p_.mode_text};
  ctx.app_frames.declare({.missed = false, .rate = true}, facts);
  const double refresh_hz = 1.0 / ctx.display_params.raster.field_period.to_seconds();
  for (const std::string& w :
       capture::presentmon_warnings(p_.source->process, p_.source->capture_period_ms, refresh_hz, false))
    ctx.recorder.warn(w);
  if (p_.source->frames_left_out > 0)
    ctx.recorder.warn(p_.pointer + ": " + std::to_string(p_.source->frames_left_out) + " of the capture's " +
                      std::to_string(p_.source->process.frames.size()) +
                      " frames lack CPU busy, CPU wait or GPU busy and are not replayed");
  ctx.display.on_retrace([this](int64_t, des::Time now) { on_retrace(now); });
  ctx.sim.spawn(application(), ctx.sim.kind("present_replay.app"));
}

// The capture's first displayed frame was flipped at a retrace: start the
// replay so that, Present for Present, it is again.
des::Time PresentReplayPipeline::start_time() const {
  des::Time offset;  // from the first frame's CPU start to the displayed frame's flip
  for (const ReplayFrame& f : p_.source->frames) {
    if (f.until_displayed) {
      offset += f.cpu_busy + *f.until_displayed;
      const display::RasterTiming& t = ctx_->display.timing();
      int64_t field = t.field_at_or_after(offset);
      return t.field_start(field) - offset;
    }
    offset += f.cpu_busy + f.in_present;
  }
  return des::Time::zero();
}

// What the runtime can know when a frame starts: its nominal CPU and GPU
// time, and the frames queued before it, each taking its refreshes.
des::Time PresentReplayPipeline::expected_photon_time() const {
  const des::Time now = ctx_->sim.now();
  const des::Time ready = now + p_.source->mean_cpu_busy + p_.source->mean_gpu_busy;
  if (p_.path.show == PresentPathSpec::Show::immediate) return ctx_->first_line_photon_time(ready);
  const display::RasterTiming& t = ctx_->display.timing();
  int64_t field = t.field_at_or_after(ready);
  if (p_.path.show == PresentPathSpec::Show::queued) {
    const int64_t behind = static_cast<int64_t>(path_.waiting()) * p_.path.sync_interval;
    field = std::max(field, t.field_at_or_before(now) + 1 + behind);
  }
  return ctx_->frame_photon_time(field + (p_.path.composed ? 1 : 0));
}

des::Process PresentReplayPipeline::application() {
  des::Simulator& sim = ctx_->sim;
  co_await sim.until(start_time());
  const std::vector<ReplayFrame>& values = p_.source->frames;
  for (int64_t j = 0;; ++j) {
    const size_t i = static_cast<size_t>(j % static_cast<int64_t>(values.size()));
    if (j > 0 && i == 0) {
      if (p_.at_end == capture::ReplayParams::AtEnd::stop) {
        // No frame more: the run ends once those presented are shown or passed over.
        stopped_ = true;
        end_if_done();
        co_return;
      }
      ++wraps_;
    }
    std::optional<tracker::PosePrediction> pose;
    // Before the first tracker sample there is nothing to read: try again shortly.
    while (!(pose = ctx_->host.pose_for(sim.now(), expected_photon_time()))) co_await sim.delay(des::Time::ms(1));
    Frame& f = frames_[j];
    f.values = &values[i];
    f.pose = *pose;
    f.cpu_start = sim.now();
    ++played_;
    co_await sim.delay(values[i].cpu_busy);
    f.present = sim.now();
    path_.presented(j);
    // Its GPU work is submitted with the present and runs after the frames before it.
    f.gpu_start = std::max(f.present, gpu_free_);
    f.gpu_end = gpu_free_ = f.gpu_start + values[i].gpu_busy;
    sim.at(f.gpu_end, kind_gpu_, [this, j] { gpu_done(j); });
    // The call lasts what it lasted in the capture, and longer while the
    // present path holds more frames than it may.
    co_await sim.delay(values[i].in_present);
    while (path_.blocks()) co_await room_;
    frames_.at(j).in_present = sim.now() - frames_.at(j).present;
    maybe_complete(j);
  }
}

void PresentReplayPipeline::gpu_done(int64_t j) {
  Frame& f = frames_.at(j);
  f.gpu_done = true;
  const des::Time now = ctx_->sim.now();
  for (int eye = 0; eye < ctx_->display.eyes(); ++eye)
    f.image_ids.push_back(ctx_->images.add(ctx_->image_record(j, eye, f.pose, f.cpu_start, now)));
  if (ctx_->timeline) {
    ctx_->timeline->add("CPU", j, -1, "application", f.cpu_start, f.present);
    ctx_->timeline->add("GPU", j, -1, "gpu", f.gpu_start, f.gpu_end);
  }
  if (path_.ready(j, now)) {
    // Tearing allowed, no interval: it replaces the front buffer now, mid-scan.
    show(j);
    if (!path_.blocks()) room_.resume();
  }
  maybe_complete(j);
}

void PresentReplayPipeline::on_retrace(des::Time now) {
  const PresentPath::Retrace r = path_.retrace(now);
  for (const int64_t j : r.discarded) {
    ++dropped_;
    settled_[j] = true;
    maybe_complete(j);
    forget(j);
  }
  for (const int64_t j : r.taken)
    if (p_.path.composed) settled_[j] = false;  // on its way through the compositor
  if (r.show) show(*r.show);
  if (!path_.blocks()) room_.resume();
}

void PresentReplayPipeline::show(int64_t j) {
  Frame& f = frames_.at(j);
  for (int eye = 0; eye < ctx_->display.eyes(); ++eye)
    ctx_->display.present_now(eye, f.image_ids[static_cast<size_t>(eye)]);
  ctx_->app_frames.flipped(j, ctx_->sim.now());
  settled_[j] = true;
  maybe_complete(j);
  forget(j);
}

// A frame's row is given once its GPU work is done and its Present has returned.
void PresentReplayPipeline::maybe_complete(int64_t j) {
  auto it = frames_.find(j);
  if (it == frames_.end() || !it->second.gpu_done || !it->second.in_present) return;
  Frame& f = it->second;
  if (!f.values) return;  // already given
  results::FrameTimes t;
  t.frame = j;
  t.has_cpu = true;
  t.cpu_start = f.cpu_start;
  t.cpu_busy = f.values->cpu_busy;
  t.present = f.present;
  t.gpu_start = f.gpu_start;
  t.gpu_end = f.gpu_end;
  t.gpu_busy = f.values->gpu_busy;
  t.in_present = f.in_present;
  ctx_->app_frames.rendered(t);
  f.values = nullptr;
  forget(j);
}

// Dropped from the books once complete and shown or passed over.
void PresentReplayPipeline::forget(int64_t j) {
  auto it = frames_.find(j);
  auto s = settled_.find(j);
  if (it == frames_.end() || it->second.values || s == settled_.end() || !s->second) return;
  frames_.erase(it);
  settled_.erase(s);
  end_if_done();
}

void PresentReplayPipeline::end_if_done() {
  if (!stopped_ || !frames_.empty() || ending_) return;
  // The last frame's field is scanned out, and lit, before the second retrace from now.
  ending_ = true;
  const display::RasterTiming& t = ctx_->display.timing();
  const des::Time end = t.field_start(t.field_at_or_after(ctx_->sim.now() + des::Time::ps(1)) + 1);
  ctx_->sim.at(end, kind_gpu_, [this] {
    ctx_->end_run_early("the capture of " + p_.pointer + " ran out after its " +
                        std::to_string(p_.source->frames.size()) +
                        " frames (at_end: stop): the figures cover the run until the last was shown");
  });
}

void PresentReplayPipeline::finish(RunContext& ctx) {
  results::LatencyRecorder& r = ctx.recorder;
  r.set("frames_dropped", dropped_);
  const ReplaySource& src = *p_.source;
  const capture::PresentMonProcess& pm = src.process;
  struct Replayed {
    const char* quantity;
    const char* column;
  };
  // The columns this run replays, by their name in the capture's generation.
  const bool v1 = pm.generation == capture::Generation::v1, v2 = pm.generation == capture::Generation::v2;
  const Replayed replayed[] = {
      {"cpu_busy", v1 ? "msBetweenPresents - msInPresentAPI" : v2 ? "CPUBusy" : "MsCPUBusy"},
      {"cpu_wait", v1 ? "msInPresentAPI" : v2 ? "CPUWait" : "MsInPresentAPI"},
      {"gpu_busy", v1 ? "msGPUActive" : v2 ? "GPUBusy" : "MsGPUBusy"},
  };
  for (const Replayed& c : replayed) {
    nlohmann::json j{{"pointer", p_.pointer},          {"file", pm.source.string()},
                     {"generation", capture::generation_name(pm.generation)},
                     {"column", c.column},             {"quantity", c.quantity},
                     {"rows_read", pm.rows_read},      {"rows_selected", static_cast<int64_t>(pm.frames.size())},
                     {"values", static_cast<int64_t>(src.frames.size())},
                     {"values_played", played_},       {"wraps", wraps_}};
    if (!pm.application.empty()) j["application"] = pm.application;
    if (pm.process_id) j["process_id"] = *pm.process_id;
    r.add_capture(j);
  }
  r.declare_headline({"motion_to_photon_ms", "application_frame_rate_hz", "frames_dropped", "frame_rate_hz"});
}

std::vector<EventRate> PresentReplayPipeline::event_rates(const sections::SharedParams& shared) const {
  // Per frame: the CPU time, the present's return and the GPU's end.
  const des::Time frame = p_.source->mean_cpu_busy + p_.source->mean_in_present;
  const double refresh_hz = 1.0 / shared.display.raster.field_period.to_seconds();
  return {{"/pipeline/capture", "present_replay", 3.0 * paced_per_s(frame, 1e6 + refresh_hz)}};
}

}  // namespace latsim::pipelines::present_replay
