// The passthrough pipeline's /pipeline keys: camera, isp, compositor, and the
// real object a rig films through the headset.
#include "latsim/sections/shared.hpp"
#include "passthrough/passthrough_pipeline.hpp"

namespace latsim::pipelines::passthrough {

namespace {

void bind_sync(scenario::Section& s, CameraSpec& p) {
  s.modes("sync", "display",
          {{"display", "phase-locked to the display: frame k opens sync_offset_ms after retrace k x refreshes_per_frame",
            [&p](scenario::Section& m) {
              p.sync = CameraSpec::Sync::display;
              m.integer("refreshes_per_frame", p.refreshes_per_frame,
                        {.min = 1.0, .max = 64.0, .doc = "display refreshes per camera frame"});
              m.duration("sync_offset_ms", p.sync_offset,
                         {.unit = "ms", .doc = "from the retrace to the first row's exposure start"});
            }},
           {"free", "free-running on a clock of its own (its phase and rate error against the display's)",
            [&p](scenario::Section& m) {
              p.sync = CameraSpec::Sync::free;
              m.rate("fps", p.frame_period, {.unit = "Hz", .doc = "camera frame rate"});
              sections::clock(m, "", p.clock, "camera");
            }}},
          {.doc = "how the camera's frames are timed against the display's"});
}

void bind_camera(scenario::Section& s, CameraSpec& p) {
  s.integer("width_px", p.width_px, {.unit = "px", .min = 1.0, .max = 16384.0, .doc = "camera image width"});
  s.integer("height_px", p.height_px, {.unit = "px", .min = 1.0, .max = 16384.0, .doc = "camera rows, read one after another"});
  s.duration("exposure_ms", p.exposure, {.unit = "ms", .doc = "each row's exposure"});
  s.choice("shutter", p.shutter, {{"global", CameraSpec::Shutter::global}, {"rolling", CameraSpec::Shutter::rolling}},
           {.doc = "global: every row exposed at once, then read row by row; rolling: row j opens j row times after "
                   "row 0 and is read as it closes"});
  s.duration("row_readout_us", p.row_readout, {.unit = "us", .doc = "per row: the frame's readout is height_px of these"});
  bind_sync(s, p);
}

void bind_isp(scenario::Section& s, IspSpec& p) {
  s.duration("fixed_ms", p.fixed, {.unit = "ms", .doc = "per frame (line-streamed: after the last row)"});
  s.number("pixel_rate_mpx_s", p.pixel_rate_mpx_s,
           {.unit = "Mpx/s", .min = 0.0, .max = 1e6, .doc = "pixels processed per second (0: no per-pixel time)"});
  s.flag("line_streamed", p.line_streamed,
         {.doc = "process rows as they are read out instead of once the whole frame is read"});
}

void bind_compositor(scenario::Section& s, CompositorSpec& p) {
  s.modes("start", "before_retrace",
          {{"before_retrace", "starts lead_ms before every retrace with the newest processed frame",
            [&p](scenario::Section& m) {
              p.start = CompositorSpec::Start::before_retrace;
              m.duration("lead_ms", p.lead, {.unit = "ms", .doc = "it starts this long before each retrace"});
            }},
           {"on_frame", "starts as soon as the ISP has a new frame (once the GPU is free)",
            [&p](scenario::Section&) { p.start = CompositorSpec::Start::on_frame; }}},
          {.doc = "when the compositor runs"});
  s.duration("reprojection_ms", p.reprojection,
             {.unit = "ms", .doc = "re-projecting the camera image to each eye's viewpoint on the GPU"});
  s.duration("composition_ms", p.composition,
             {.unit = "ms", .doc = "composing rendered content over it (0: passthrough alone)"});
}

void check_camera(scenario::Section& s, const CameraSpec& c, const sections::SharedParams& shared) {
  const double refresh_s = shared.display.raster.field_period.to_seconds();
  const double frame_s =
      c.sync == CameraSpec::Sync::display ? refresh_s * c.refreshes_per_frame : c.frame_period.to_seconds();
  s.check("camera", c.exposure.to_seconds() <= frame_s, "the exposure must fit in a camera frame period");
  s.check("camera", c.readout().to_seconds() <= frame_s,
          "the readout (height_px x row_readout_us) must fit in a camera frame period");
  if (c.sync == CameraSpec::Sync::display)
    s.check("camera", c.sync_offset.to_seconds() < frame_s, "sync_offset_ms must be shorter than a camera frame period");
}

}  // namespace

/// Reads /pipeline of a passthrough scenario (found by pipeline_entry through its Params).
void bind(scenario::Section& s, PassthroughPipeline::Params& p, const sections::SharedParams& shared) {
  PassthroughSpec& spec = p.spec;
  s.object("camera", spec.camera, bind_camera, {.doc = "the see-through camera"});
  s.object("isp", spec.isp, bind_isp, {.doc = "the image signal processor"});
  s.object("compositor", spec.compositor, bind_compositor, {.doc = "re-projection and composition on the headset's GPU"});
  std::optional<tracker::MotionParams> object;
  s.optional_object("object", object, [](scenario::Section& o, tracker::MotionParams& v) { sections::bind(o, v); },
                    {.doc = "a real object moving in front of the headset (the motions of /motion), for the rig"});
  std::optional<measurement::CameraRigParams> rig;
  s.optional_object("rig", rig,
                    [](scenario::Section& r, measurement::CameraRigParams& v) {
                      sections::bind(r, v, "a passthrough rig films the real object of /pipeline/object beside its "
                                           "image, never a controller: leave object out");
                    },
                    {.doc = "the rig of latsim filming /pipeline/object and its image at display_point: the keys of "
                            "/measurement, whose object key can only be head here and is not used"});
  s.check("rig", !rig || object, "the rig films /pipeline/object: give one");
  if (rig && object) {
    spec.rig = RigSpec{*object, *rig};
    spec.point = rig->display_point;
  }
  check_camera(s, spec.camera, shared);
  const double refresh_s = shared.display.raster.field_period.to_seconds();
  const CompositorSpec& c = spec.compositor;
  s.check("compositor", c.lead.to_seconds() < refresh_s && (c.reprojection + c.composition).to_seconds() <= refresh_s,
          "the compositor's lead and time must be shorter than a refresh");
}

}  // namespace latsim::pipelines::passthrough

namespace latsim::pipelines {

PipelineEntry passthrough_pipeline() {
  return pipeline_entry<passthrough::PassthroughPipeline>(
      "passthrough",
      "A see-through headset: a camera (exposure, global or rolling shutter, row readout, phase-locked to the display "
      "or free-running), an image signal processor, a compositor re-projecting the newest camera frame to the eye's "
      "viewpoint with the newest head pose and composing rendered content, the display; photon-to-photon latency "
      "at a point with each stage's share, and a rig filming a moving real object through it (docs/passthrough.md).");
}

}  // namespace latsim::pipelines
