// Pixel-Planes 5 Rendering Control as a latsim pipeline.
#include <memory>

#include "latsim/pipelines/pipeline.hpp"
#include "latsim/pxpl5/rc_engine.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "pxpl5/event_rates.hpp"
#include "pxpl5/wiring.hpp"

namespace latsim::pipelines {

namespace {

/// "pxpl5_rc": SEND, EDIT, TRANSFORM, RENDER and COPY with the published start conditions.
class Pxpl5RcPipeline final : public Pipeline {
 public:
  struct Params {
    pxpl5::RcParams rc;
    Pxpl5Common common;
  };

  explicit Pxpl5RcPipeline(const Params& p) : p_(p) {}

  void start(RunContext& ctx) override {
    wiring_ = std::make_unique<Pxpl5Wiring>(ctx);
    p_.rc.stereo = p_.common.stereo;
    // RC's latency follows the load, so the host expects the next frame to
    // take as long from its pose read to its last COPY as the newest
    // finished frame did, and to be swapped in at the retrace after that.
    wiring_->expect_photon_time([this, &ctx](des::Time t) { return ctx.photon_time_after(t + wiring_->read_to_copy_end()); });
    engine_ = std::make_unique<pxpl5::RcEngine>(ctx.sim, p_.rc, wiring_->field_timing(), wiring_->grid(),
                                                wiring_->workload(p_.common), wiring_->hooks());
    // A host that waits for the tracker wakes when a sample becomes visible (no events otherwise).
    if (p_.rc.host_waits_for_new_sample)
      ctx.host.on_delivery([this](const tracker::TrackerSample&, des::Time) { engine_->sample_visible(); });
    engine_->start(ctx.sim.now() + ctx.duration);
  }

  void finish(RunContext& ctx) override {
    wiring_->report(engine_->utilisation(ctx.duration), engine_->frames_completed());
    ctx.recorder.declare_headline({"motion_to_photon_ms", "render_latency_fields", "frame_rate_hz",
                                   "missed_refreshes"});
  }

  std::vector<EventRate> event_rates(const sections::SharedParams& shared) const override {
    return rc_event_rates(p_.rc, p_.common, shared);
  }

 private:
  Params p_;
  std::unique_ptr<Pxpl5Wiring> wiring_;
  std::unique_ptr<pxpl5::RcEngine> engine_;
};

void bind(scenario::Section& s, Pxpl5RcPipeline::Params& p, const sections::SharedParams& shared) {
  pxpl5::RcParams& r = p.rc;
  bind_hardware(s, r.hw);
  s.integer("graphics_processors", r.graphics_processors, {.min = 2.0, .max = 256.0, .doc = "one master plus the slaves"});
  s.duration("send_us", r.send_time, {.unit = "us", .doc = "host: edits and viewing transforms"});
  s.integer("send_words", r.send_words, {.min = 0.0, .max = 16777216.0, .doc = "edit commands on the ring per frame"});
  s.duration("edit_us", r.edit_time, {.unit = "us", .doc = "slaves apply edits to their display lists"});
  s.duration("transform_overhead_us", r.transform_overhead, {.unit = "us", .doc = "per slave and eye: matrices, bin reset"});
  s.duration("transform_us_per_triangle", r.transform_time_per_triangle,
             {.unit = "us", .doc = "one eye, a triangle on screen: transform, clip, light, set up (i860 at 40 MHz)"});
  s.duration("reject_us_per_triangle", r.reject_time_per_triangle,
             {.unit = "us", .doc = "one eye, a triangle outside the view: transform its corners, clip test (view workload)"});
  s.duration("binitize_us_per_bin", r.binitize_time_per_bin, {.unit = "us", .doc = "one command into one region's bin"});
  s.duration("sphere_transform_us", r.sphere_transform_time,
             {.unit = "us", .doc = "one eye, a sphere on screen: transform its centre and radius, set up its quadratics"});
  s.duration("sphere_reject_us", r.sphere_reject_time,
             {.unit = "us", .doc = "one eye, a sphere outside the view: transform its centre, clip test"});
  s.integer("words_per_sphere_command", r.words_per_sphere_command,
            {.min = 1.0, .max = 4096.0, .doc = "one sphere for one eye: disk, z and normal quadratics, colour"});
  s.check("max_message_words", r.hw.max_message_words >= r.words_per_sphere_command,
          "must hold at least one sphere command (words_per_sphere_command)");
  s.duration("render_us_per_sphere_command", r.render_time_per_sphere_command,
             {.unit = "us", .doc = "one sphere command into one region (quadratic expressions)"});
  s.duration("token_hop_us", r.token_hop_time, {.unit = "us", .doc = "a region token from one processor to the next"});
  s.duration("region_shade_us", r.region_shade_time, {.unit = "us", .doc = "end-of-frame (deferred shading) commands"});
  s.integer("end_of_frame_words", r.end_of_frame_words, {.min = 0.0, .max = 1048576.0, .doc = "end-of-frame commands on the ring"});
  s.object(
      "host", r,
      [](scenario::Section& h, pxpl5::RcParams& rc) {
        h.choice("read", rc.host_read, {{"send_start", pxpl5::HostRead::send_start}, {"late", pxpl5::HostRead::late}},
                 {.doc = "send_start: the tracker is read as SEND starts; late: as EDIT starts, when the slaves "
                         "first need the viewing transforms"});
        h.flag("wait_for_new_sample", rc.host_waits_for_new_sample,
               {.doc = "SEND first waits until the host sees a tracker sample newer than the previous frame's (an "
                       "application blocking on the tracker; examined in docs/pxpl5.md)"});
      },
      {.doc = "when the host reads the tracker, and whether it waits for a new sample"});
  s.flag("copy_holds_renderer", r.copy_holds_renderer,
         {.doc = "a region's COPY holds the renderer that rendered it, as Slats' copies do (an assumption: "
                 "docs/pxpl5.md)"});
  s.choice("swap_at", r.swap_at,
           {{"any_field", pxpl5::SwapAt::any_field}, {"frame_start", pxpl5::SwapAt::frame_start}},
           {.doc = "any_field: the first retrace after the pair's COPY; frame_start: on an interlaced display only "
                   "a retrace that starts a frame (an assumption: docs/pxpl5.md)"});
  s.choice("stereo_swap", r.stereo_swap,
           {{"together", pxpl5::StereoSwap::together}, {"per_eye", pxpl5::StereoSwap::per_eye}},
           {.doc = "together: both frame buffers swap after the pair's last COPY (SPEC.md section 4); per_eye: each "
                   "after its own eye's COPY (examined against the published minimum case: docs/pxpl5.md)"});
  bind_pxpl5_common(s, shared, r.hw, p.common);
  // What one frame of the synthetic workload costs must fit the run's clock.
  const double triangles = static_cast<double>(p.common.synthetic.triangles) * (p.common.stereo ? 2.0 : 1.0);
  const double bins = triangles * p.common.synthetic.regions_per_triangle;
  s.check_span("transform_us_per_triangle", r.transform_time_per_triangle.to_seconds(), triangles,
               "/scene/triangles per frame");
  s.check_span("binitize_us_per_bin", r.binitize_time_per_bin.to_seconds(), bins,
               "/scene/triangles × regions_per_triangle per frame");
  s.check_span("render_us_per_command", r.hw.render_time_per_command.to_seconds(), bins,
               "/scene/triangles × regions_per_triangle per frame");
  // Every bin's commands, the edits and each region's end-of-frame commands cross the ring.
  const double s_per_word = 1.0 / (r.hw.ring_mwords_per_s * 1e6);
  const double eyes = p.common.stereo ? 2.0 : 1.0;
  const display::RasterParams& raster = shared.display.raster;
  const double regions = pxpl5::RegionGrid::for_screen(raster.width_px, raster.height_px, raster.interlaced, 128).regions();
  s.check_span("ring_mwords_per_s", s_per_word,
               bins * r.hw.words_per_command + r.send_words + eyes * regions * r.end_of_frame_words,
               "ring words per frame (bins × words_per_command, send_words, end_of_frame_words per region)");
  // With the view workload the triangles come from the geometry, counted when the run builds it.
  const std::string& at = s.pointer();
  p.common.view_spans = {{at + "/ring_mwords_per_s", s_per_word * r.hw.words_per_command, true, true},{at + "/transform_us_per_triangle", r.transform_time_per_triangle.to_seconds(), true, false},
                         {at + "/reject_us_per_triangle", r.reject_time_per_triangle.to_seconds(), true, false},
                         {at + "/binitize_us_per_bin", r.binitize_time_per_bin.to_seconds(), true, true},
                         {at + "/render_us_per_command", r.hw.render_time_per_command.to_seconds(), true, true},
                         {at + "/sphere_transform_us", r.sphere_transform_time.to_seconds(), true, false, true},
                         {at + "/render_us_per_sphere_command", r.render_time_per_sphere_command.to_seconds(), true,
                          true, true}};
  p.common.draws_spheres = true;
}

}  // namespace

PipelineEntry pxpl5_rc_pipeline() {
  return pipeline_entry<Pxpl5RcPipeline>(
      "pxpl5_rc",
      "Pixel-Planes 5 Rendering Control: SEND, EDIT, TRANSFORM, RENDER and COPY as processes with the published start "
      "conditions (see docs/pxpl5.md). Reads /scene's `triangles` and `regions_per_triangle`, or with "
      "`workload: view` its geometry.");
}

}  // namespace latsim::pipelines
