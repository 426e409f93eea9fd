// Pixel-Planes 5 Rendering Control as a latsim pipeline, plus the wiring
// both Pixel-Planes 5 pipelines share.
#include <memory>

#include "latsim/pipelines/latency_recorder.hpp"
#include "latsim/pipelines/pxpl5.hpp"
#include "latsim/pipelines/timeline.hpp"
#include "latsim/pxpl5/rc_engine.hpp"
#include "latsim/pxpl5/workload.hpp"

namespace latsim::pipelines {

namespace {

nlohmann::json summary_json(const des::Distribution& d) {
  const des::Distribution::Summary s = d.summary();
  return {{"count", s.count}, {"mean", s.mean},   {"stddev", s.stddev}, {"min", s.min}, {"p50", s.p50},
          {"p90", s.p90},     {"p99", s.p99},     {"p999", s.p999},     {"max", s.max}};
}

// Samples older than this many tracker periods can no longer be asked for.
constexpr int64_t kSamplesKept = 256;

}  // namespace

Pxpl5Wiring::Pxpl5Wiring(RunContext& ctx) : ctx_(&ctx) {}

pxpl5::FieldTiming Pxpl5Wiring::field_timing() const {
  const display::RasterTiming& t = ctx_->display.timing();
  return pxpl5::FieldTiming(t.field_start(0), t.params().field_period, t.params().vblank_lines, t.lines_per_field());
}

pxpl5::RegionGrid Pxpl5Wiring::grid() const {
  const display::RasterParams& p = ctx_->display.timing().params();
  return pxpl5::RegionGrid::for_screen(p.width_px, p.height_px, p.interlaced, 128);
}

int64_t Pxpl5Wiring::remember(const tracker::TrackerSample& sample) {
  samples_[sample.index] = sample;
  while (!samples_.empty() && samples_.begin()->first < sample.index - kSamplesKept) samples_.erase(samples_.begin());
  return sample.index;
}

pxpl5::EngineHooks Pxpl5Wiring::hooks() {
  pxpl5::EngineHooks h;
  h.newest_sample = [this](des::Time t) -> int64_t {
    const auto s = ctx_->host.newest_at(t);
    return s ? remember(*s) : -1;
  };
  h.frame_ready = [this](const pxpl5::FrameReady& f) { present(f); };
  if (ctx_->timeline != nullptr)
    h.stage = [this](const pxpl5::StageInterval& s) {
      ctx_->timeline->add(s.stage, s.frame, s.eye, s.unit, s.start, s.end);
    };
  h.sample = [this](const std::string& name, double v) { samples_by_name_[name].add(v); };
  return h;
}

// Each eye's image is registered with the sample it was computed from and
// swapped in at the next retrace (both eyes together in stereo).
void Pxpl5Wiring::present(const pxpl5::FrameReady& f) {
  for (const pxpl5::EyeImage& e : f.eyes) {
    const auto it = samples_.find(e.sample_token);
    if (it == samples_.end()) {
      ++images_without_sample_;  // nothing tracked yet: the display keeps what it has
      continue;
    }
    ImageRecord rec = ctx_->image_record(f.frame, e.eye, it->second, e.transform_start, e.copy_end);
    const int64_t id = ctx_->recorder.register_image(rec);
    ctx_->display.present_at_next_retrace(e.eye, id);
  }
}

void Pxpl5Wiring::add_figures(nlohmann::json& figures, const pxpl5::Utilisation& u, int64_t missed_fields,
                              int64_t torn_fields, int64_t frames_completed) const {
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [name, dist] : samples_by_name_) {
    if (name.rfind("stage_ms.", 0) == 0)
      stages[name.substr(9)] = summary_json(dist);
    else if (name != "missed_field")
      figures[name] = summary_json(dist);
  }
  figures["stage_ms"] = stages;
  figures["utilisation"] = {{"gp", u.gp}, {"renderer", u.renderer}, {"ring", u.ring}, {"copy", u.copy}};
  figures["missed_fields"] = missed_fields;
  figures["torn_fields"] = torn_fields;
  figures["frames_completed"] = frames_completed;
  figures["images_without_sample"] = images_without_sample_;
  for (const char* name : {"render_latency_fields", "copy_ms_per_frame"})
    if (!figures.contains(name)) figures[name] = summary_json(des::Distribution{});
}

namespace {

/// "pxpl5_rc": SEND, EDIT, TRANSFORM, RENDER and COPY with the published start conditions.
class Pxpl5RcPipeline final : public Pipeline {
 public:
  std::string name() const override { return "pxpl5_rc"; }

  void start(RunContext& ctx) override {
    wiring_ = std::make_unique<Pxpl5Wiring>(ctx);
    const pxpl5::RcParams params = pxpl5::RcParams::read(ctx.pipeline, ctx.stereo);
    const pxpl5::Workload workload = pxpl5::Workload::read(ctx.root.child("scene"));
    engine_ = std::make_unique<pxpl5::RcEngine>(ctx.sim, params, wiring_->field_timing(), wiring_->grid(), workload,
                                                ctx.stream("pxpl5.bins"), wiring_->hooks());
    engine_->start(ctx.sim.now() + ctx.duration);
  }

  void finish(RunContext& ctx, nlohmann::json& figures) override {
    wiring_->add_figures(figures, engine_->utilisation(ctx.duration), 0, 0, engine_->frames_completed());
  }

 private:
  std::unique_ptr<Pxpl5Wiring> wiring_;
  std::unique_ptr<pxpl5::RcEngine> engine_;
};

}  // namespace

void register_pxpl5_pipelines(PipelineRegistry& registry) {
  registry.add("pxpl5_rc", [] { return std::make_unique<Pxpl5RcPipeline>(); });
  registry.add("pxpl5_slats", [] { return make_pxpl5_slats_pipeline(); });
}

}  // namespace latsim::pipelines
