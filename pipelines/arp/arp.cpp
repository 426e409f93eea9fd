// Plain address recalculation: the whole scene is rendered into one cube
// display memory at the rendering rate from the position of the newest
// sample; at scanout the display looks every pixel up in the cube with the
// newest orientation, so rotation latency does not depend on the rendering
// rate while translation latency does.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "latsim/arp/memory_frames.hpp"
#include "latsim/arp/scene_config.hpp"
#include "latsim/pipelines/arp.hpp"
#include "latsim/pipelines/latency_recorder.hpp"
#include "latsim/pipelines/timeline.hpp"
#include "latsim/renderer/png_writer.hpp"

namespace latsim::pipelines {
namespace {

glm::vec3 read_colour(const scenario::ConfigNode& node, std::string_view key, glm::vec3 def) {
  const std::vector<double> v = node.numbers(key, {def.r, def.g, def.b});
  if (v.size() != 3) node.fail(key, "a colour needs three linear components [r, g, b]");
  return glm::vec3(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
}

/// One cube display memory, re-rendered at a fixed rate, viewed by address recalculation.
class ArpPipeline final : public Pipeline {
 public:
  std::string name() const override { return "arp"; }

  void start(RunContext& ctx) override {
    ctx_ = &ctx;
    const auto& p = ctx.pipeline;
    const des::RationalSeconds period = p.rate_as_period("render_rate_hz", "60");
    render_time_ = p.duration_ms("render_time_ms", 5.0);
    if (render_time_ > des::PeriodicSchedule(des::Time::zero(), period).nominal_period() || render_time_ <= des::Time::zero())
      p.fail("render_time_ms", "must be positive and at most one rendering period");
    face_px_ = static_cast<int>(p.integer("face_px", 256, 1, 8192));
    background_ = read_colour(p, "background", glm::vec3(1.0f));
    frame_times_s_ = p.numbers("frame_times_s", {});
    threads_ = static_cast<int>(p.integer("frame_threads", 1, 1, 256));
    scene_node_ = ctx.root.optional_child("scene");
    if (scene_node_) object_count_ = arp::scene_from_config(*scene_node_).object_count();
    // The display's field of view, read where the runner reads it.
    if (const auto display = ctx.root.optional_child("display")) hfov_deg_ = display->number("hfov_deg", 90.0);
    schedule_ = des::PeriodicSchedule(des::Time::zero(), period);
    kind_render_ = ctx.sim.kind("arp.render");
    kind_frame_ = ctx.sim.kind("arp.frame");
    schedule_render(0);
    if (wants_frames()) {
      for (double t : frame_times_s_) {
        const des::Time at = des::Time::from_seconds(t);
        if (at >= des::Time::zero() && at < ctx.duration) ctx.sim.at(at, kind_frame_, [this] { write_frame(); }, 10);
      }
    }
  }

  void finish(RunContext& ctx, nlohmann::json& figures) override {
    const double duration_s = ctx.duration.to_seconds();
    nlohmann::json memory = {{"update_rate_hz", static_cast<double>(renders_) / duration_s},
                             {"segments", object_count_},
                             {"renders", renders_}};
    figures["memories"] = nlohmann::json::array({memory});
    figures["render_load"] = static_cast<double>(renders_ * object_count_) / duration_s;
    figures["renders_without_pose"] = skipped_;
  }

 private:
  bool wants_frames() const {
    return (ctx_->frames != nullptr || !frame_times_s_.empty()) && scene_node_.has_value() && !ctx_->out_dir.empty();
  }

  void schedule_render(int64_t k) {
    const des::Time at = schedule_.at(k);
    if (at >= ctx_->duration) return;
    ctx_->sim.at(at, kind_render_, [this, k] { begin_render(k); });
  }

  void begin_render(int64_t k, bool first_attempt = true) {
    if (first_attempt) schedule_render(k + 1);
    const auto sample = ctx_->host.newest_at(ctx_->sim.now());
    if (!sample) {
      // Before the first sample reaches the host: try again shortly within this slot.
      const des::Time retry = ctx_->sim.now() + des::Time::ms(1);
      if (retry < schedule_.at(k + 1) && retry < ctx_->duration) {
        ctx_->sim.at(retry, kind_render_, [this, k] { begin_render(k, false); });
      } else {
        ++skipped_;
      }
      return;
    }
    const des::Time start = ctx_->sim.now();
    const tracker::TrackerSample s = *sample;
    ctx_->sim.after(render_time_, kind_render_, [this, s, start, k] { end_render(s, start, k); });
  }

  void end_render(const tracker::TrackerSample& s, des::Time start, int64_t k) {
    ++renders_;
    // Display memories are double-buffered: the new cube is used from the next field on.
    ctx_->present_display_memory(k, s, start, "arp");
  }

  // The cube shown now: rendered from the position of the image in the front buffer.
  void write_frame() {
    const int64_t front = ctx_->display.front(0);
    const ImageRecord* img = front >= 0 ? ctx_->recorder.image(front) : nullptr;
    const auto newest = ctx_->host.newest_at(ctx_->sim.now());
    if (!img || !newest) return;
    if (!renderer_) {
      segmented_ = std::make_unique<arp::SegmentedScene>();
      segmented_->scene = arp::scene_from_config(*scene_node_);
      renderer_ = std::make_unique<arp::MemoryRenderer>(*segmented_, face_px_, background_, threads_);
    }
    const renderer::CubeMap cube = renderer_->render_all(img->eye_pose.position_m);
    const auto& raster = ctx_->display.timing().params();
    const renderer::Camera camera(hfov_deg_, raster.width_px, raster.height_px);
    const renderer::CubeMap* cubes[] = {&cube};
    const renderer::Frame frame = arp::view_through_cubes(cubes, camera, newest->pose.orientation, background_);
    const auto ms = static_cast<int64_t>(ctx_->sim.now().to_ms());
    renderer::write_png(ctx_->out_dir / ("arp_frame_" + std::to_string(ms) + "ms.png"), frame.colour);
  }

  RunContext* ctx_ = nullptr;
  des::PeriodicSchedule schedule_;
  des::Time render_time_;
  int face_px_ = 256;
  int threads_ = 1;
  glm::vec3 background_{1.0f};
  std::vector<double> frame_times_s_;
  std::optional<scenario::ConfigNode> scene_node_;
  double hfov_deg_ = 90.0;
  int64_t object_count_ = 0;
  des::KindId kind_render_ = 0;
  des::KindId kind_frame_ = 0;
  int64_t renders_ = 0;
  int64_t skipped_ = 0;
  std::unique_ptr<arp::SegmentedScene> segmented_;
  std::unique_ptr<arp::MemoryRenderer> renderer_;
};

}  // namespace

std::unique_ptr<Pipeline> make_arp_pipeline() { return std::make_unique<ArpPipeline>(); }

void register_arp_pipelines(PipelineRegistry& registry) {
  registry.add("arp", make_arp_pipeline);
  registry.add("priority", make_priority_pipeline);
  registry.add("region_priority", make_region_priority_pipeline);
}

}  // namespace latsim::pipelines
