#include "pxpl5/event_rates.hpp"

#include <algorithm>
#include <cmath>

#include "latsim/renderer/scene_spec.hpp"

namespace latsim::pipelines {

namespace {

// Events per unit of work, counted from the engines' processes (each a
// resumption of a process that waited): a ring transfer waits for a channel
// and for its transfer time; a renderer waits for its inbox and for its
// work; a region copy waits for the region, the frame-buffer port, the
// ring and the copy time.
constexpr double kEventsPerTransfer = 2.0;
constexpr double kEventsPerRender = 2.0;
constexpr double kEventsPerCopy = 4.0;
// Rendering Control's renderer per region: a token hop for every slave, and
// for a slave with commands a port, the ring and the transfer.
constexpr double kEventsPerHop = 1.0;
// The host, per sample it sends (Slats) or per frame (RC): a wake, the ring and the transfer.
constexpr double kEventsPerSend = 3.0;

double fields_per_s_of(const sections::SharedParams& shared) {
  return 1.0 / shared.display.raster.field_period.to_seconds();
}

pxpl5::RegionGrid grid_of(const sections::SharedParams& shared) {
  const display::RasterParams& r = shared.display.raster;
  return pxpl5::RegionGrid::for_screen(r.width_px, r.height_px, r.interlaced, 128);
}

}  // namespace

std::vector<EventRate> slats_event_rates(const pxpl5::SlatsParams& p, const Pxpl5Common& common,
                                         const sections::SharedParams& shared) {
  const double eyes = common.stereo ? 2.0 : 1.0;
  const double triangles = static_cast<double>(common.synthetic.triangles);
  // The GP starts a field at a retrace once it is free: one per refresh at most.
  const double gp_field_s = p.gp_field_overhead.to_seconds() + p.gp_time_per_triangle.to_seconds() * triangles;
  const double fields_per_s = paced_per_s(gp_field_s, fields_per_s_of(shared));
  const bool gp_bound = gp_field_s * fields_per_s_of(shared) > 1.0;
  const std::string field_key = gp_bound ? "/pipeline/gp_us_per_triangle" : "/display/refresh_hz";
  // Each full message goes to every renderer over the ring and is rendered there.
  const double per_message =
      std::max(1.0, std::floor(p.hw.max_message_words / (static_cast<double>(p.hw.words_per_command) * eyes)));
  const double messages = std::max(1.0, std::ceil(triangles / per_message));
  const double per_message_events = 1.0 + p.hw.renderers * (kEventsPerTransfer + kEventsPerRender);
  const double regions = eyes * grid_of(shared).field_regions();
  const double tracker_hz = 1.0 / shared.tracker.period.to_seconds();
  return {{"/scene/triangles", "pxpl5", fields_per_s * messages * per_message_events},
          {field_key, "pxpl5", fields_per_s * (regions * kEventsPerCopy + 2.0)},
          // Every delivered sample is an event and goes to the GP as a SEND.
          {"/tracker/rate_hz", "transport", tracker_hz},
          {"/tracker/rate_hz", "pxpl5", tracker_hz * kEventsPerSend}};
}

// Triangles one image transforms as on screen. With the view workload the
// view decides, from none to all of the geometry's (spheres counted as
// triangles): half of them keeps the estimate within a factor of two of
// either end's transform time.
double rc_triangles_in_view(const Pxpl5Common& common, const sections::SharedParams& shared) {
  if (common.workload != Pxpl5WorkloadKind::view || !shared.scene) return static_cast<double>(common.synthetic.triangles);
  const renderer::Scene scene = renderer::make_scene(shared.scene->geometry, renderer::SphereForm::native);
  return 0.5 * static_cast<double>(scene.triangles().size() + scene.spheres().size());
}

std::vector<EventRate> rc_event_rates(const pxpl5::RcParams& p, const Pxpl5Common& common,
                                      const sections::SharedParams& shared) {
  const double eyes = common.stereo ? 2.0 : 1.0;
  const double triangles = rc_triangles_in_view(common, shared);
  const double bins = triangles * common.synthetic.regions_per_triangle;
  const double slaves = p.slaves();
  const double regions = grid_of(shared).regions();
  // A frame's slowest stage, per eye: the slaves' transform, or the
  // renderers' share of the regions' commands and token hops.
  const double transform_s = p.transform_overhead.to_seconds() +
                             (p.transform_time_per_triangle.to_seconds() * triangles +
                              p.binitize_time_per_bin.to_seconds() * bins) / slaves;
  const double render_s = (p.hw.render_time_per_command.to_seconds() * bins +
                           regions * (slaves * p.token_hop_time.to_seconds() + p.region_shade_time.to_seconds())) /
                          p.hw.renderers;
  const double frame_s = eyes * std::max(transform_s, render_s);
  // COPY waits for the previous frame's swap at a retrace: one frame per refresh at most.
  const double fields_per_s = fields_per_s_of(shared);
  const double frames_per_s = frame_s > 0.0 ? std::min(fields_per_s, 1.0 / frame_s) : fields_per_s;
  const std::string key = frame_s * fields_per_s > 1.0
                              ? (transform_s >= render_s ? "/pipeline/transform_us_per_triangle"
                                                         : "/pipeline/render_us_per_command")
                              : "/display/refresh_hz";
  // Per region: every slave's token hop, the transfer of the slaves holding
  // its commands (at most all of them), the end-of-frame transfer, the
  // shading wait and the copy.
  const double holders = std::min(slaves, std::max(1.0, common.synthetic.regions_per_triangle * triangles / regions));
  // A copy that holds its renderer waits for it too; a swap held back to a
  // frame's start hands the frame over one event later.
  const double per_region = slaves * kEventsPerHop + holders * (kEventsPerTransfer + 1.0) + kEventsPerTransfer + 2.0 +
                            kEventsPerCopy + (p.copy_holds_renderer ? 2.0 : 0.0);
  const double per_frame = kEventsPerSend + 4.0 + (p.swap_at == pxpl5::SwapAt::frame_start ? 1.0 : 0.0);
  std::vector<EventRate> rates{{key, "pxpl5", frames_per_s * (eyes * regions * per_region + per_frame)}};
  if (p.host_waits_for_new_sample) {
    // Every sample becomes visible as an event, and may wake the waiting host.
    const double tracker_hz = 1.0 / shared.tracker.period.to_seconds();
    rates.push_back({"/tracker/rate_hz", "transport", tracker_hz});
    rates.push_back({"/tracker/rate_hz", "pxpl5", tracker_hz});
  }
  return rates;
}

}  // namespace latsim::pipelines
