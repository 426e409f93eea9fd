// Priority rendering on address recalculation: every object's validity period
// is estimated at each tick of the maximum update rate from the newest
// tracker sample, objects move between display memories updated at harmonic
// rates, a memory is redrawn only when one of its images would expire, and
// the redraws share the renderers, fastest memory first.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "arp/memory_display.hpp"
#include "arp/render_keys.hpp"
#include "latsim/arp/priority_system.hpp"
#include "latsim/des/periodic.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/renderer/scene_spec.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "latsim/scenario/section.hpp"
#include "latsim/units/units.hpp"

namespace latsim::pipelines {
namespace {

/// Drives a PrioritySystem from the host's samples and shows its composite image.
class PriorityPipeline final : public Pipeline {
 public:
  /// An object whose own animation limits how long its image stays valid.
  struct Animated {
    std::string object;
    double validity_s = 1.0;
    std::string pointer;  ///< where the scenario names it, for errors
  };
  struct Params {
    arp::PriorityParams model;
    int face_px = 256;
    double threshold_angle_deg = 0.0;
    arp::MemoryRenderCost cost{.per_pixel_ns = 2.0};
    int renderers = 1;
    std::vector<Animated> animated;
    des::ClockSettings loop;  ///< the tick loop's own clock
  };

  explicit PriorityPipeline(const Params& p) : p_(p) {}

  void start(RunContext& ctx) override {
    ctx_ = &ctx;
    ctx.fetch_orientation_at_scanout();
    scene_ = renderer::make_scene(ctx.scene->geometry);
    std::vector<arp::PriorityObject> objects;
    for (const auto& obj : scene_.objects()) objects.push_back({obj.bounds, 0.0, glm::dvec3(0.0)});
    for (const Animated& a : p_.animated) {
      try {
        objects.at(scene_.find_object(a.object)).animation_validity_s = a.validity_s;
      } catch (const renderer::SceneError&) {
        throw scenario::ScenarioError(a.pointer, "the scene has no object \"" + a.object + "\"");
      }
    }
    object_count_ = static_cast<int64_t>(objects.size());
    // One update may draw every object of the scene.
    scenario::check_span_at("/pipeline/render_per_object_us", p_.cost.per_segment.to_seconds(),
                            static_cast<double>(object_count_), "the scene's objects");
    system_.emplace(ctx.sim, ctx.sim.kind("arp.priority_render"), scene_, std::move(objects),
                    arp::PrioritySystemParams{p_.model, p_.cost, p_.renderers, p_.face_px});
    system_->memories().on_present([this](const std::vector<const arp::MemoryImage*>& batch) { present(batch); });
    ctx.recorder.expects_images();
    const des::Clock& loop = ctx.clock("loop", "/pipeline/loop_phase_ms", p_.model.base_period, p_.loop);
    ticks_.emplace(ctx.sim, loop.schedule(), ctx.sim.kind("arp.priority_tick"), [this](int64_t k) { tick(k); });
    ticks_->start(0, ctx.duration);
  }

  // A tick at the fastest memory's rate, and at most one render completion
  // per memory per tick (a memory is redrawn at most once per its own slot).
  std::vector<EventRate> event_rates(const sections::SharedParams&) const override {
    const double ticks_per_s = 1.0 / p_.model.base_period.to_seconds();
    return {{"/pipeline/max_update_rate_hz", "arp", ticks_per_s * (1.0 + p_.model.memory_count)}};
  }

  void finish(RunContext& ctx) override {
    const double duration_s = ctx.duration.to_seconds();
    results::LatencyRecorder& r = ctx.recorder;
    // Address recalculation reads the orientation per line at scanout: its
    // rotation latency is the point; positions come with the renders.
    r.declare_headline({"rotation_latency_ms", "translation_latency_ms", "registration_error_arcmin",
                        "motion_to_photon_ms"});
    const arp::PriorityModel& model = system_->model();
    const arp::DisplayMemories& memories = system_->memories();
    int64_t rendered = 0;
    int64_t skipped = 0;
    const auto lists = model.objects_per_memory();
    for (int m = 0; m < model.memories().count(); ++m) {
      const arp::MemoryRenderCounts& c = memories.counts(m);
      const double renders = static_cast<double>(c.renders);
      const std::string at = "memories." + std::to_string(m) + ".";
      r.set(at + "memory", int64_t{m});
      r.set(at + "nominal_rate_hz", model.memories().rate_hz(m));
      r.set(at + "update_rate_hz", renders / duration_s);
      r.set(at + "segments", c.renders > 0 ? static_cast<double>(c.object_segments) / renders : 0.0);
      r.set(at + "pixels", c.renders > 0 ? c.texels / renders : 0.0);
      r.set(at + "objects_at_end", static_cast<int64_t>(lists[static_cast<size_t>(m)].size()));
      r.set(at + "renders", c.renders);
      r.set(at + "renders_skipped", memories.queue().skipped(m));
      rendered += c.object_segments;
      skipped += memories.queue().skipped(m);
    }
    const double utilisation = memories.queue().utilisation(ctx.duration);
    r.set("render_load", static_cast<double>(rendered) / duration_s);
    // What redrawing every object at the maximum rate would cost, for comparison.
    r.set("render_load_all_at_max_rate", static_cast<double>(object_count_) / model.memories().period_s(0));
    r.set("promotions", model.promotions());
    r.set("demotions", model.demotions());
    r.set("renders_skipped", skipped);
    r.set("renderer_utilisation", utilisation);
    r.publish("render_queue_ms", memories.queue().queue_ms());
    if (skipped > 0 || utilisation > 0.95) {
      r.warn("priority: the renderers cannot keep up: " + std::to_string(skipped) +
             " renders skipped, renderer utilisation " + std::to_string(utilisation));
    }
  }

 private:
  void tick(int64_t k) {
    const auto sample = ctx_->host.newest_at(ctx_->sim.now());
    if (!sample) return;
    // Velocity from the two newest distinct samples; zero until there are two.
    if (!last_ || last_->index != sample->index) {
      if (last_ && sample->measured_at > last_->measured_at) {
        velocity_m_s_ = (sample->pose.position_m - last_->pose.position_m) /
                        (sample->measured_at - last_->measured_at).to_seconds();
      }
      last_ = sample;
    }
    // Memories are drawn from the pose predicted for their first field: the
    // host expects this render to take as long as the last one did.
    const des::Time now = ctx_->sim.now();
    const tracker::PosePrediction pose =
        ctx_->host.basis_of(*sample).for_photon_time(ctx_->photon_time_after(now + last_render_time_));
    samples_.add(k, pose);
    const arp::PriorityTick& t = system_->tick(k, now, pose.pose.position_m, velocity_m_s_, k);
    if (!t.updated_memories.empty()) {
      ctx_->recorder.add("objects_rendered_per_tick", static_cast<double>(t.objects_rendered));
      // The updated display memories are meant to be in use by the next tick.
      ctx_->recorder.image_due(ticks_->schedule().at(k + 1));
    }
  }

  void present(const std::vector<const arp::MemoryImage*>& batch) {
    show_memory_images(*ctx_, batch, samples_);
    if (!batch.empty()) last_render_time_ = batch.back()->cost;
    samples_.forget_unreachable(system_->memories());
  }

  Params p_;
  RunContext* ctx_ = nullptr;
  renderer::Scene scene_;
  std::optional<arp::PrioritySystem> system_;
  std::optional<des::Periodic> ticks_;
  int64_t object_count_ = 0;
  std::optional<tracker::TrackerSample> last_;
  des::Time last_render_time_;
  glm::dvec3 velocity_m_s_{0.0};
  SampleBook samples_;
};


void bind(scenario::Section& s, PriorityPipeline::Params& p, const sections::SharedParams& shared) {
  s.rate("max_update_rate_hz", p.model.base_period, {.unit = "Hz", .max = 1e4, .doc = "rate of the fastest display memory (and of the ticks)"});
  s.integer("memory_count", p.model.memory_count, {.min = 1.0, .max = 16.0, .doc = "display memories at rates halving from the fastest"});
  s.integer("face_px", p.face_px, {.unit = "px", .min = 1.0, .max = 8192.0, .doc = "cube display memory face size"});
  // Default threshold: one texel of the cube memory at a face centre.
  p.threshold_angle_deg = 90.0 / p.face_px;
  s.number("threshold_angle_deg", p.threshold_angle_deg,
           {.unit = "deg", .min = 1e-9, .max = 90.0, .doc = "error an image may reach before it is redrawn",
            .default_doc = "90 / face_px (one texel)"});
  p.model.threshold_rad = p.threshold_angle_deg * units::kRadPerDeg;
  bind_render_costs(s, p.cost, p.renderers, "render_per_object_us", "object drawn");
  sections::clock(s, "loop_", p.loop, "tick loop");
  s.objects("animated", p.animated,
            [](scenario::Section& a, PriorityPipeline::Animated& v) {
              a.doc("An object whose own animation limits how long its image stays valid.");
              a.text("object", v.object, {.required = true, .doc = "the scene object's name"});
              v.pointer = scenario::join_pointer(a.pointer(), "object");
              a.number("validity_s", v.validity_s,
                       {.unit = "s", .min = 0.0, .above_min = true, .required = true, .doc = "how long its image stays valid"});
            },
            {.doc = "animated objects (none when absent)"});
  s.check_pointer("/scene", shared.scene.has_value(), "priority rendering needs a scene");
}

}  // namespace

PipelineEntry priority_pipeline() {
  return pipeline_entry<PriorityPipeline>(
      "priority",
      "Priority rendering on address recalculation: each object's validity period is estimated at every tick of "
      "the maximum update rate, objects move between display memories updated at harmonic rates (at the slower "
      "memory's slot), and a memory is redrawn only when one of its images would expire, by renderers shared "
      "fastest memory first (see docs/arp.md). Needs a /scene.");
}

}  // namespace latsim::pipelines
