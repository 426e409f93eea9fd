// Pixel-Planes 5 Rendering Control as a latsim pipeline, plus the wiring
// both Pixel-Planes 5 pipelines share.
#include <memory>

#include "latsim/pipelines/latency_recorder.hpp"
#include "latsim/pipelines/timeline.hpp"
#include "latsim/pxpl5/rc_engine.hpp"
#include "pxpl5/wiring.hpp"

namespace latsim::pipelines {

namespace {

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

void Pxpl5Wiring::report(const pxpl5::Utilisation& u, int64_t missed_fields, int64_t torn_fields,
                         int64_t frames_completed) const {
  LatencyRecorder& r = ctx_->recorder;
  r.object("stage_ms");
  for (const auto& [name, dist] : samples_by_name_)
    if (name != "missed_field") r.publish(name, dist);
  r.set("utilisation.gp", u.gp);
  r.set("utilisation.renderer", u.renderer);
  r.set("utilisation.ring", u.ring);
  r.set("utilisation.copy", u.copy);
  r.set("missed_fields", missed_fields);
  r.set("torn_fields", torn_fields);
  r.set("frames_completed", frames_completed);
  r.set("images_without_sample", images_without_sample_);
  for (const char* name : {"render_latency_fields", "copy_ms_per_frame"})
    if (!samples_by_name_.count(name)) r.publish(name, des::Distribution{});
}

void bind_hardware(scenario::Section& s, pxpl5::HardwareParams& h) {
  s.integer("ring_channels", h.ring_channels, {.min = 1.0, .max = 64.0, .doc = "independent channels of the ring"});
  s.number("ring_mwords_per_s", h.ring_mwords_per_s,
           {.unit = "Mword/s", .min = 0.0, .above_min = true, .doc = "per channel (8 × 20 = 160 Mwords/s in all)"});
  s.integer("renderers", h.renderers, {.min = 1.0, .max = 256.0, .doc = "renderer boards"});
  s.integer("frame_buffers", h.frame_buffers, {.min = 1.0, .max = 2.0, .doc = "one per eye in stereo"});
  s.integer("words_per_command", h.words_per_command,
            {.min = 1.0, .max = 4096.0, .doc = "one Gouraud triangle for one eye: edge, z and colour planes"});
  s.integer("max_message_words", h.max_message_words, {.min = 1.0, .max = 1048576.0, .doc = "largest ring message"});
  s.check("max_message_words", h.max_message_words >= h.words_per_command,
          "must hold at least one command (words_per_command)");
  s.duration("copy_us_per_region", h.copy_time_per_region,
             {.unit = "us", .min = 0.0, .above_min = true, .doc = "renderer to frame buffer, one 128 × 128 region"});
  s.duration("render_us_per_command", h.render_time_per_command,
             {.unit = "us", .doc = "one triangle command into one region"});
}

void bind_pxpl5_scene(scenario::Section& s, const params::SharedParams& shared, const pxpl5::HardwareParams& hw,
                      bool& stereo, pxpl5::Workload& workload) {
  stereo = shared.host.stereo;
  s.check("frame_buffers", !(stereo && hw.frame_buffers < 2), "stereo needs one frame buffer per eye (2)");
  s.check_pointer("/scene", shared.scene.has_value(), "Pixel-Planes 5 needs a scene (its triangles)");
  // Every triangle is dealt to a bin one by one.
  s.check_pointer("/scene/triangles", !shared.scene || shared.scene->triangles <= 100'000'000,
                  "Pixel-Planes 5 simulates each triangle: at most 1e8");
  if (!shared.scene) return;
  workload.triangles = shared.scene->triangles;
  workload.regions_per_triangle = shared.scene->regions_per_triangle;
}

namespace {

/// "pxpl5_rc": SEND, EDIT, TRANSFORM, RENDER and COPY with the published start conditions.
class Pxpl5RcPipeline final : public Pipeline {
 public:
  struct Params {
    pxpl5::RcParams rc;
    pxpl5::Workload workload;
  };

  explicit Pxpl5RcPipeline(const Params& p) : p_(p) {}

  void start(RunContext& ctx) override {
    wiring_ = std::make_unique<Pxpl5Wiring>(ctx);
    engine_ = std::make_unique<pxpl5::RcEngine>(ctx.sim, p_.rc, wiring_->field_timing(), wiring_->grid(), p_.workload,
                                                ctx.stream("pxpl5.bins"), wiring_->hooks());
    engine_->start(ctx.sim.now() + ctx.duration);
  }

  void finish(RunContext& ctx) override {
    wiring_->report(engine_->utilisation(ctx.duration), 0, 0, engine_->frames_completed());
  }

 private:
  Params p_;
  std::unique_ptr<Pxpl5Wiring> wiring_;
  std::unique_ptr<pxpl5::RcEngine> engine_;
};

void bind(scenario::Section& s, Pxpl5RcPipeline::Params& p, const params::SharedParams& shared) {
  pxpl5::RcParams& r = p.rc;
  bind_hardware(s, r.hw);
  s.integer("graphics_processors", r.graphics_processors, {.min = 2.0, .max = 256.0, .doc = "one master plus the slaves"});
  s.duration("send_us", r.send_time, {.unit = "us", .doc = "host: edits and viewing transforms"});
  s.integer("send_words", r.send_words, {.min = 0.0, .max = 16777216.0, .doc = "edit commands on the ring per frame"});
  s.duration("edit_us", r.edit_time, {.unit = "us", .doc = "slaves apply edits to their display lists"});
  s.duration("transform_overhead_us", r.transform_overhead, {.unit = "us", .doc = "per slave and eye: matrices, bin reset"});
  s.duration("transform_us_per_triangle", r.transform_time_per_triangle, {.unit = "us", .doc = "one eye, i860 at 40 MHz"});
  s.duration("binitize_us_per_bin", r.binitize_time_per_bin, {.unit = "us", .doc = "one command into one region's bin"});
  s.duration("token_hop_us", r.token_hop_time, {.unit = "us", .doc = "a region token from one processor to the next"});
  s.duration("region_shade_us", r.region_shade_time, {.unit = "us", .doc = "end-of-frame (deferred shading) commands"});
  s.integer("end_of_frame_words", r.end_of_frame_words, {.min = 0.0, .max = 1048576.0, .doc = "end-of-frame commands on the ring"});
  bind_pxpl5_scene(s, shared, r.hw, r.stereo, p.workload);
}

}  // namespace

PipelineEntry pxpl5_rc_pipeline() {
  return pipeline_entry<Pxpl5RcPipeline>(
      "pxpl5_rc",
      "Pixel-Planes 5 Rendering Control: SEND, EDIT, TRANSFORM, RENDER and COPY as processes with the published start "
      "conditions (see docs/pxpl5.md). Reads /scene's `triangles` and `regions_per_triangle`.");
}

}  // namespace latsim::pipelines
