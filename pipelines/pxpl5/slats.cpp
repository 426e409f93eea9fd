// Pixel-Planes 5 Slats as a latsim pipeline: field-synchronous rendering fed
// by an asynchronous host.
#include <memory>

#include "latsim/pxpl5/slats_engine.hpp"
#include "pxpl5/wiring.hpp"

namespace latsim::pipelines {

namespace {

/// "pxpl5_slats": one GP, both eyes per pass, static region binding, one field of latency.
class Pxpl5SlatsPipeline final : public Pipeline {
 public:
  struct Params {
    pxpl5::SlatsParams slats;
    pxpl5::Workload workload;
  };

  explicit Pxpl5SlatsPipeline(const Params& p) : p_(p) {}

  void start(RunContext& ctx) override {
    wiring_ = std::make_unique<Pxpl5Wiring>(ctx);
    // Slats renders one bin of every triangle, so only the count matters.
    engine_ = std::make_unique<pxpl5::SlatsEngine>(ctx.sim, p_.slats, wiring_->field_timing(), wiring_->grid(),
                                                   p_.workload.triangles, wiring_->hooks());
    // SEND is asynchronous: every sample the host sees goes to the GP.
    ctx.host.on_delivery([this](const tracker::TrackerSample& s, des::Time) {
      engine_->host_sample(wiring_->remember(s));
    });
    engine_->start(ctx.sim.now() + ctx.duration);
  }

  void finish(RunContext& ctx) override {
    wiring_->report(engine_->utilisation(ctx.duration), engine_->missed_fields(), engine_->torn_fields(),
                    engine_->fields_shown());
  }

 private:
  Params p_;
  std::unique_ptr<Pxpl5Wiring> wiring_;
  std::unique_ptr<pxpl5::SlatsEngine> engine_;
};

void bind(scenario::Section& s, Pxpl5SlatsPipeline::Params& p, const params::SharedParams& shared) {
  pxpl5::SlatsParams& q = p.slats;
  bind_hardware(s, q.hw);
  s.duration("gp_us_per_triangle", q.gp_time_per_triangle,
             {.unit = "us", .doc = "both eyes, one pass: transform, clip, light, set up plane equations twice"});
  s.duration("gp_field_overhead_us", q.gp_field_overhead, {.unit = "us", .doc = "take the newest transforms, set up, flush"});
  s.duration("region_finish_us", q.region_finish_time, {.unit = "us", .doc = "Gouraud: no deferred shading, just wrap up"});
  s.duration("host_compute_us", q.host_compute_time, {.unit = "us", .doc = "host: both eyes' viewing transforms"});
  s.integer("host_message_words", q.host_message_words, {.min = 0.0, .max = 1048576.0, .doc = "host to processor message"});
  s.flag("copy_optimisation", q.copy_optimisation,
         {.doc = "lower regions may arrive until the beam reaches them; false: every region by the retrace"});
  s.flag("backup_field", q.backup_field, {.doc = "show a backup of the last complete field instead of a torn one"});
  bind_pxpl5_scene(s, shared, q.hw, q.stereo, p.workload);
}

}  // namespace

PipelineEntry pxpl5_slats_pipeline() {
  return pipeline_entry<Pxpl5SlatsPipeline>(
      "pxpl5_slats",
      "Pixel-Planes 5 Slats: field-synchronous rendering of both eyes by one processor with static region binding, "
      "fed by an asynchronous host; one field of rendering latency (see docs/pxpl5.md). Reads /scene's `triangles`.");
}

}  // namespace latsim::pipelines
