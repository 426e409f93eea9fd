// Plain address recalculation: the whole scene is rendered into one cube
// display memory at the rendering rate from the position of the newest
// sample; at scanout the display looks every pixel up in the cube with the
// newest orientation, so rotation latency does not depend on the rendering
// rate while translation latency does.
#include <optional>
#include <string>
#include <vector>

#include "arp/frames.hpp"
#include "latsim/arp/memory_frames.hpp"
#include "latsim/des/periodic.hpp"
#include "latsim/des/process.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "latsim/results/run_files.hpp"
#include "latsim/results/timeline.hpp"

namespace latsim::pipelines {
namespace {

/// One cube display memory, re-rendered at a fixed rate, viewed by address recalculation.
class ArpPipeline final : public Pipeline {
 public:
  struct Params {
    des::RationalSeconds render_period{1, 60};
    des::Time render_time = des::Time::ms(5);
    des::ClockSettings loop;  ///< the rendering loop's own clock
    FrameOptions frames;
  };

  explicit ArpPipeline(const Params& p) : p_(p) {}

  void start(RunContext& ctx) override {
    ctx_ = &ctx;
    ctx.fetch_orientation_at_scanout();
    if (ctx.scene) object_count_ = renderer::make_scene(ctx.scene->geometry).object_count();
    ctx.recorder.expects_images();
    const des::KindId kind_render = ctx.sim.kind("arp.render");
    const des::Clock& loop = ctx.clock("loop", "/pipeline/loop_phase_ms", p_.render_period, p_.loop);
    ticks_.emplace(ctx.sim, loop.schedule(), kind_render,
                   [this, kind_render](int64_t k) { ctx_->sim.start(render(k), kind_render); });
    ticks_->start(0, ctx.duration);
    if ((ctx.frames != nullptr || !p_.frames.times_s.empty()) && ctx.scene && ctx.files.enabled())
      schedule_frames(ctx, p_.frames, [this] { write_frame(); });
  }

  void finish(RunContext& ctx) override {
    const double duration_s = ctx.duration.to_seconds();
    results::LatencyRecorder& r = ctx.recorder;
    // Address recalculation reads the orientation per line at scanout: its
    // rotation latency is the point; positions come with the renders.
    r.declare_headline({"rotation_latency_ms", "translation_latency_ms", "registration_error_arcmin",
                        "motion_to_photon_ms"});
    r.set("memories.0.update_rate_hz", static_cast<double>(renders_) / duration_s);
    r.set("memories.0.segments", object_count_);
    r.set("memories.0.renders", renders_);
    r.set("render_load", static_cast<double>(renders_ * object_count_) / duration_s);
    r.set("renders_without_pose", skipped_);
  }

  // Each tick of the rendering loop starts a render that ends one render time later.
  std::vector<EventRate> event_rates(const sections::SharedParams&) const override {
    return {{"/pipeline/render_rate_hz", "arp", 2.0 / p_.render_period.to_seconds()}};
  }

 private:
  // Render k starts at its tick from the newest sample; before the first
  // sample reaches the host it retries every millisecond within its slot.
  des::Process render(int64_t k) {
    const des::Time slot_end = ticks_->schedule().at(k + 1);
    std::optional<tracker::PosePrediction> pose;
    // The cube is used from the first retrace after it is rendered.
    while (!(pose = ctx_->host.pose_for(ctx_->sim.now(), ctx_->photon_time_after(ctx_->sim.now() + p_.render_time)))) {
      const des::Time retry = ctx_->sim.now() + des::Time::ms(1);
      if (retry >= slot_end || retry >= ctx_->duration) {
        ++skipped_;
        co_return;
      }
      co_await ctx_->sim.until(retry);
    }
    const des::Time start = ctx_->sim.now();
    // The new display memory is meant to be in use by the next tick.
    ctx_->recorder.image_due(slot_end);
    co_await ctx_->sim.delay(p_.render_time);
    ++renders_;
    // Display memories are double-buffered: the new cube is used from the next field on.
    ctx_->present_display_memory(k, *pose, start, "arp");
  }

  // The cube shown now: rendered from the position of the image in the front buffer.
  void write_frame() {
    const int64_t front = ctx_->display.front(0);
    const results::ImageRecord* img = front >= 0 ? ctx_->images.find(front) : nullptr;
    // The orientation the next field is looked up with (its middle line).
    const auto newest = ctx_->host.pose_for(ctx_->sim.now(), ctx_->photon_time_after(ctx_->sim.now()));
    if (!img || !newest) return;
    if (!renderer_) {
      segmented_ = std::make_unique<arp::SegmentedScene>();
      segmented_->scene = renderer::make_scene(ctx_->scene->geometry);
      renderer_ = std::make_unique<arp::MemoryRenderer>(*segmented_, p_.frames.face_px, p_.frames.background,
                                                        p_.frames.threads);
    }
    const renderer::CubeMap cube = renderer_->render_all(img->eye_pose.position_m);
    const auto& raster = ctx_->display.timing().params();
    const renderer::Camera camera(ctx_->display_params.hfov_deg, raster.width_px, raster.height_px);
    const renderer::CubeMap* cubes[] = {&cube};
    const renderer::Frame frame = arp::view_through_cubes(cubes, camera, newest->pose.orientation, p_.frames.background);
    const auto ms = static_cast<int64_t>(ctx_->sim.now().to_ms());
    ctx_->files.write_png("arp_frame_" + std::to_string(ms) + "ms.png", frame.colour);
  }

  Params p_;
  RunContext* ctx_ = nullptr;
  std::optional<des::Periodic> ticks_;
  int64_t object_count_ = 0;
  int64_t renders_ = 0;
  int64_t skipped_ = 0;
  std::unique_ptr<arp::SegmentedScene> segmented_;
  std::unique_ptr<arp::MemoryRenderer> renderer_;
};

void bind(scenario::Section& s, ArpPipeline::Params& p, const sections::SharedParams&) {
  s.rate("render_rate_hz", p.render_period, {.unit = "Hz", .doc = "how often the cube display memory is re-rendered"});
  s.duration("render_time_ms", p.render_time, {.unit = "ms", .doc = "time to render the cube"});
  s.check("render_time_ms",
          p.render_time > des::Time::zero() &&
              p.render_time <= des::PeriodicSchedule(des::Time::zero(), p.render_period).nominal_period(),
          "must be positive and at most one rendering period");
  sections::clock(s, "loop_", p.loop, "rendering loop");
  bind(s, p.frames);
}

}  // namespace

PipelineEntry arp_pipeline() {
  return pipeline_entry<ArpPipeline>(
      "arp",
      "Address recalculation: the scene is rendered into a cube display memory at its own rate; at scanout every "
      "pixel is looked up with the newest orientation, so rotation latency does not depend on the rendering rate "
      "while translation latency does (see docs/arp.md). Draws the /scene when it writes frames.");
}

}  // namespace latsim::pipelines
