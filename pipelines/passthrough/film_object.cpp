// The rig of latsim filming the real object beside its image through the
// headset: photon-to-photon latency as a camera measures it.
#include "latsim/measurement/panel_rise.hpp"
#include "latsim/results/figure_writer.hpp"
#include "passthrough/passthrough_pipeline.hpp"

namespace latsim::pipelines::passthrough {

namespace {

// What the rig's camera sees of each new value at the point: the panel's transition.
measurement::PanelRise panel_rise(const display::Persistence& persistence) {
  measurement::PanelRise rise;
  if (!persistence.configured()) return rise;
  using Rise = display::PersistenceParams::Rise;
  const display::PersistenceParams& pp = persistence.params();
  rise.response = pp.response;
  rise.curve = pp.rise == Rise::linear        ? measurement::PanelRise::Curve::linear
               : pp.rise == Rise::exponential ? measurement::PanelRise::Curve::exponential
                                              : measurement::PanelRise::Curve::step;
  return rise;
}

}  // namespace

void PassthroughPipeline::film_object(RunContext& ctx) {
  const measurement::CameraRigParams& rig = spec_.rig->rig;
  const measurement::DisplaySignal display(lit_, panel_rise(ctx.display.persistence()));
  const des::Time exposure = rig.exposure ? *rig.exposure : rig_camera_->nominal_period();
  const measurement::RigResult r = measurement::film(*object_signal_, display, *rig_camera_, exposure, ctx.duration, rig);
  results::FigureWriter& w = ctx.figures;
  for (const double v : r.frame_counting_ms) w.add("photon_to_photon_rig_ms", v);
  for (const double v : r.shift_ms) w.add("photon_to_photon_rig_shift_ms", v);
  w.set("photon_to_photon_rig_resolution_ms", r.resolution_ms);
  w.set("photon_to_photon_rig_movements", static_cast<int64_t>(r.frame_counting_ms.size()));
  if (r.frame_counting_ms.empty())
    w.warn("the rig saw no movement of the real object from rest to rest (photon_to_photon_rig_movements is 0): "
           "/pipeline/object must rest for /pipeline/rig/rest_ms between movements larger than "
           "/pipeline/rig/threshold_deg");
}

}  // namespace latsim::pipelines::passthrough
