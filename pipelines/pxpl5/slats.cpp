// Pixel-Planes 5 Slats as a latsim pipeline: field-synchronous rendering fed
// by an asynchronous host.
#include <algorithm>
#include <memory>

#include "latsim/pipelines/pipeline.hpp"
#include "latsim/pxpl5/slats_engine.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "pxpl5/event_rates.hpp"
#include "pxpl5/wiring.hpp"

namespace latsim::pipelines {

namespace {

/// "pxpl5_slats": one GP, both eyes per pass, static region binding, one field of latency.
class Pxpl5SlatsPipeline final : public Pipeline {
 public:
  struct Params {
    pxpl5::SlatsParams slats;
    Pxpl5Common common;
  };

  explicit Pxpl5SlatsPipeline(const Params& p) : p_(p) {}

  void start(RunContext& ctx) override {
    wiring_ = std::make_unique<Pxpl5Wiring>(ctx);
    p_.slats.stereo = p_.common.stereo;
    engine_ = std::make_unique<pxpl5::SlatsEngine>(ctx.sim, p_.slats, wiring_->field_timing(), wiring_->grid(),
                                                   wiring_->workload(p_.common), wiring_->hooks());
    // SEND is asynchronous: every sample the host sees goes to the GP, which
    // takes the newest at the first retrace after it arrives and shows that
    // field's image one field later; the host predicts for that field.
    const des::Time send = p_.slats.host_compute_time + p_.slats.hw.transfer_time(p_.slats.host_message_words);
    wiring_->expect_photon_time([&ctx, send](des::Time t) { return ctx.photon_time_after(t + send, 1); });
    ctx.host.on_delivery([this](const tracker::TrackerSample& s, des::Time t) {
      engine_->host_sample(wiring_->remember(s, t));
    });
    engine_->start(ctx.sim.now() + ctx.duration);
    // Once the processor holds viewing transforms, every field is due a new
    // image by the next retrace (the engine starts it at this one).
    ctx.display.on_retrace([this, &ctx](int64_t, des::Time now) {
      if (wiring_->transforms_sent()) ctx.recorder.image_due(now + des::Time::ps(1));
    });
  }

  std::vector<EventRate> event_rates(const sections::SharedParams& shared) const override {
    return slats_event_rates(p_.slats, p_.common, shared);
  }

  void finish(RunContext& ctx) override {
    const pxpl5::FieldCounts& c = engine_->counts();
    wiring_->report(engine_->utilisation(ctx.duration), c.complete);
    results::LatencyRecorder& r = ctx.recorder;
    r.declare_headline({"motion_to_photon_ms", "render_latency_fields", "missed_fields", "missed_field_fraction"});
    r.set("missed_fields", c.missed);
    r.set("missed_field_fraction", c.missed_fraction());
    r.set("torn_fields", c.torn);
    r.set("fields_never_started", c.never_started);
    r.set("backup_copies", c.backup_copies);
    if (c.missed > 0)
      r.warn("Slats missed " + std::to_string(c.missed) + " of " + std::to_string(c.complete + c.missed) +
             " fields: their work did not fit (see missed_fields, torn_fields, deadline_slack_ms)");
  }

 private:
  Params p_;
  std::unique_ptr<Pxpl5Wiring> wiring_;
  std::unique_ptr<pxpl5::SlatsEngine> engine_;
};

void bind(scenario::Section& s, Pxpl5SlatsPipeline::Params& p, const sections::SharedParams& shared) {
  pxpl5::SlatsParams& q = p.slats;
  bind_hardware(s, q.hw);
  s.duration("gp_us_per_triangle", q.gp_time_per_triangle,
             {.unit = "us", .doc = "a triangle on screen, both eyes in one pass: transform, clip, light, set up plane "
                                   "equations twice"});
  s.duration("gp_us_per_rejected_triangle", q.gp_time_per_rejected_triangle,
             {.unit = "us", .doc = "a triangle outside both eyes' views: transform its corners twice, clip test"});
  s.duration("gp_field_overhead_us", q.gp_field_overhead, {.unit = "us", .doc = "take the newest transforms, set up, flush"});
  s.duration("region_finish_us", q.region_finish_time, {.unit = "us", .doc = "Gouraud: no deferred shading, just wrap up"});
  s.duration("host_compute_us", q.host_compute_time, {.unit = "us", .doc = "host: both eyes' viewing transforms"});
  s.integer("host_message_words", q.host_message_words, {.min = 0.0, .max = 1048576.0, .doc = "host to processor message"});
  s.flag("copy_optimisation", q.copy_optimisation,
         {.doc = "lower regions may arrive until the beam reaches them; false: every region by the retrace"});
  s.flag("backup_field", q.backup_field,
         {.doc = "a late region is replaced by its backup from the last complete field, copied like any region"});
  // Lower regions are written while the field is being scanned out; a display
  // that samples the whole field at its retrace would show them a field late.
  s.check_pointer("/display/scanout", shared.display.fidelity != display::ScanoutFidelity::Field,
                  "Slats writes regions into the displayed frame buffer during scanout: use \"line\" or \"pixel\"");
  bind_pxpl5_common(s, shared, q.hw, p.common);
  // What one field of the synthetic workload costs must fit the run's clock; every region renders the one bin.
  const double triangles = static_cast<double>(p.common.synthetic.triangles);
  s.check_span("gp_us_per_triangle", q.gp_time_per_triangle.to_seconds(), triangles, "/scene/triangles per field");
  s.check_span("render_us_per_command", q.hw.render_time_per_command.to_seconds(), triangles * 20.0,
               "/scene/triangles × 20 regions per field");
  // The ring carries every message to each renderer: a field's words must cross it within the run's clock.
  const double s_per_triangle = q.hw.words_per_command * (p.common.stereo ? 2.0 : 1.0) * q.hw.renderers /
                                (q.hw.ring_mwords_per_s * 1e6);
  s.check_span("ring_mwords_per_s", s_per_triangle, triangles,
               "/scene/triangles × words_per_command × eyes × renderers per field");
  s.check_span("ring_mwords_per_s", 1.0 / (q.hw.ring_mwords_per_s * 1e6),
               static_cast<double>(std::max(q.host_message_words, q.hw.max_message_words)), "the largest message's words");
  // With the view workload the triangles come from the geometry, counted when the run builds it.
  const std::string& at = s.pointer();
  p.common.view_spans = {{at + "/ring_mwords_per_s", s_per_triangle, false, false},
                         {at + "/gp_us_per_triangle", q.gp_time_per_triangle.to_seconds(), false, false},
                         {at + "/gp_us_per_rejected_triangle", q.gp_time_per_rejected_triangle.to_seconds(), false, false},
                         {at + "/render_us_per_command", q.hw.render_time_per_command.to_seconds(), false, true}};
}

}  // namespace

PipelineEntry pxpl5_slats_pipeline() {
  return pipeline_entry<Pxpl5SlatsPipeline>(
      "pxpl5_slats",
      "Pixel-Planes 5 Slats: field-synchronous rendering of both eyes by one processor with static region binding, "
      "fed by an asynchronous host, as processes on the GP, ring channels, renderers and frame-buffer ports (see "
      "docs/pxpl5.md). Reads /scene's `triangles`, or with `workload: view` its geometry.");
}

}  // namespace latsim::pipelines
