// Priority rendering on address recalculation: every object's validity period
// is estimated at each tick of the maximum update rate from the newest
// tracker sample, objects move between display memories updated at harmonic
// rates, and a memory is redrawn only when one of its images would expire.
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "latsim/arp/priority_model.hpp"
#include "latsim/arp/scene_config.hpp"
#include "latsim/pipelines/arp.hpp"
#include "latsim/pipelines/latency_recorder.hpp"
#include "latsim/pipelines/timeline.hpp"

namespace latsim::pipelines {
namespace {

/// Drives a PriorityModel from the host's samples and shows its composite image.
class PriorityPipeline final : public Pipeline {
 public:
  std::string name() const override { return "priority"; }

  void start(RunContext& ctx) override {
    ctx_ = &ctx;
    const auto& p = ctx.pipeline;
    arp::PriorityParams params;
    params.base_period = p.rate_as_period("max_update_rate_hz", "60");
    params.memory_count = static_cast<int>(p.integer("memory_count", 4, 1, 16));
    const int face_px = static_cast<int>(p.integer("face_px", 256, 1, 8192));
    // Default threshold: one texel of the cube memory at a face centre.
    params.threshold_rad = p.number_in("threshold_angle_deg", 90.0 / face_px, 1e-9, 90.0) * kDegToRad;
    fixed_time_ = p.duration_ms("render_fixed_ms", 1.0);
    per_object_ = des::Time::from_us(p.non_negative("render_per_object_us", 20.0));
    const renderer::Scene scene = arp::scene_from_config(ctx.root.child("scene"));
    std::vector<arp::PriorityObject> objects;
    for (const auto& obj : scene.objects()) objects.push_back({obj.bounds, 0.0, glm::dvec3(0.0)});
    const std::vector<scenario::ConfigNode> animated =
        p.has("animated") ? p.objects("animated") : std::vector<scenario::ConfigNode>{};
    for (const auto& a : animated) {
      const std::string object = a.string("object");
      const double validity_s = a.positive("validity_s");
      try {
        objects.at(scene.find_object(object)).animation_validity_s = validity_s;
      } catch (const renderer::SceneError&) {
        a.fail("object", "the scene has no object \"" + object + "\"");
      }
    }
    object_count_ = static_cast<int64_t>(objects.size());
    model_.emplace(std::move(objects), params);
    schedule_ = des::PeriodicSchedule(des::Time::zero(), params.base_period);
    kind_tick_ = ctx.sim.kind("arp.priority_tick");
    kind_done_ = ctx.sim.kind("arp.priority_render");
    schedule_tick(0);
  }

  void finish(RunContext& ctx, nlohmann::json& figures) override {
    const double duration_s = ctx.duration.to_seconds();
    nlohmann::json memories = nlohmann::json::array();
    int64_t rendered = 0;
    const auto lists = model_->objects_per_memory();
    for (int m = 0; m < model_->memories().count(); ++m) {
      const arp::MemoryCounters& c = model_->counters()[static_cast<size_t>(m)];
      memories.push_back({{"memory", m},
                          {"nominal_rate_hz", model_->memories().rate_hz(m)},
                          {"update_rate_hz", static_cast<double>(c.renders) / duration_s},
                          {"segments", c.renders > 0 ? static_cast<double>(c.objects_rendered) / c.renders : 0.0},
                          {"objects_at_end", lists[static_cast<size_t>(m)].size()},
                          {"renders", c.renders}});
      rendered += c.objects_rendered;
    }
    figures["memories"] = memories;
    figures["render_load"] = static_cast<double>(rendered) / duration_s;
    // What redrawing every object at the maximum rate would cost, for comparison.
    figures["render_load_all_at_max_rate"] = static_cast<double>(object_count_) / model_->memories().period_s(0);
    figures["promotions"] = model_->promotions();
    figures["demotions"] = model_->demotions();
  }

 private:
  static constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

  void schedule_tick(int64_t k) {
    const des::Time at = schedule_.at(k);
    if (at >= ctx_->duration) return;
    ctx_->sim.at(at, kind_tick_, [this, k] { tick(k); });
  }

  void tick(int64_t k) {
    schedule_tick(k + 1);
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
    const des::Time now = ctx_->sim.now();
    const arp::PriorityTick t = model_->tick(k, now, sample->pose.position_m, velocity_m_s_);
    if (t.updated_memories.empty()) return;
    ctx_->recorder.add("objects_rendered_per_tick", static_cast<double>(t.objects_rendered));
    const des::Time end = now + fixed_time_ + per_object_ * t.objects_rendered;
    const tracker::TrackerSample s = *sample;
    ctx_->sim.at(end, kind_done_, [this, s, now, k] { present(s, now, k); });
  }

  void present(const tracker::TrackerSample& s, des::Time start, int64_t k) {
    ctx_->present_display_memory(k, s, start, "priority");
  }

  RunContext* ctx_ = nullptr;
  std::optional<arp::PriorityModel> model_;
  des::PeriodicSchedule schedule_;
  des::Time fixed_time_;
  des::Time per_object_;
  int64_t object_count_ = 0;
  des::KindId kind_tick_ = 0;
  des::KindId kind_done_ = 0;
  std::optional<tracker::TrackerSample> last_;
  glm::dvec3 velocity_m_s_{0.0};
};

}  // namespace

std::unique_ptr<Pipeline> make_priority_pipeline() { return std::make_unique<PriorityPipeline>(); }

}  // namespace latsim::pipelines
