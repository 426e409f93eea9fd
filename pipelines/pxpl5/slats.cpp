// Pixel-Planes 5 Slats as a latsim pipeline: field-synchronous rendering fed
// by an asynchronous host.
#include <memory>

#include "latsim/pipelines/pxpl5.hpp"
#include "latsim/pxpl5/slats_engine.hpp"
#include "latsim/pxpl5/workload.hpp"

namespace latsim::pipelines {

namespace {

/// "pxpl5_slats": one GP, both eyes per pass, static region binding, one field of latency.
class Pxpl5SlatsPipeline final : public Pipeline {
 public:
  std::string name() const override { return "pxpl5_slats"; }

  void start(RunContext& ctx) override {
    wiring_ = std::make_unique<Pxpl5Wiring>(ctx);
    const pxpl5::SlatsParams params = pxpl5::SlatsParams::read(ctx.pipeline, ctx.stereo);
    // Slats renders one bin of every triangle, so only the count matters.
    const pxpl5::Workload workload = pxpl5::Workload::read(ctx.root.child("scene"));
    engine_ = std::make_unique<pxpl5::SlatsEngine>(ctx.sim, params, wiring_->field_timing(), wiring_->grid(),
                                                   workload.triangles, wiring_->hooks());
    // SEND is asynchronous: every sample the host sees goes to the GP.
    ctx.host.on_delivery([this](const tracker::TrackerSample& s, des::Time) {
      engine_->host_sample(wiring_->remember(s));
    });
    engine_->start(ctx.sim.now() + ctx.duration);
  }

  void finish(RunContext& ctx, nlohmann::json& figures) override {
    wiring_->add_figures(figures, engine_->utilisation(ctx.duration), engine_->missed_fields(),
                         engine_->torn_fields(), engine_->fields_shown());
  }

 private:
  std::unique_ptr<Pxpl5Wiring> wiring_;
  std::unique_ptr<pxpl5::SlatsEngine> engine_;
};

}  // namespace

std::unique_ptr<Pipeline> make_pxpl5_slats_pipeline() { return std::make_unique<Pxpl5SlatsPipeline>(); }

}  // namespace latsim::pipelines
