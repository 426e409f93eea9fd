#include "latsim/pipelines/event_rate.hpp"

#include <algorithm>
#include <cmath>

namespace latsim::pipelines {

double paced_per_s(des::Time period, double cap_hz) { return paced_per_s(period.to_seconds(), cap_hz); }

double paced_per_s(double period_s, double cap_hz) {
  if (period_s <= 0.0) return cap_hz;
  return std::min(cap_hz, 1.0 / period_s);
}

namespace {

// Work done outside the event queue, counted as steps: the motion-phase grid,
// apparent latency's windows, the camera rig's frames.
void add_measurement_rates(const sections::SharedParams& p, double fields_per_s, std::vector<EventRate>& rates) {
  const double duration_s = p.duration_s;
  // Motion phases classify the head's motion step by step up to every instant
  // asked about (apparent latency classifies with the defaults), photon times
  // included: those lie a display's pixel response past their writes, so a
  // response longer than the run costs its own steps.
  if (p.motion_phases || p.apparent_latency) {
    const des::Time step = p.motion_phases.value_or(tracker::MotionPhaseParams{}).step;
    if (step > des::Time::zero()) {
      const double per_s = 1.0 / step.to_seconds();
      rates.push_back({p.motion_phases ? "/motion_phases/step_ms" : "/apparent_latency", "motion_phases", per_s, true});
      const auto& persistence = p.display.persistence;
      if (persistence && persistence->response > des::Time::zero() && duration_s > 0.0)
        rates.push_back({"/display/persistence/response_ms", "motion_phases",
                         persistence->response.to_seconds() * per_s / duration_s, true});
    }
  }
  // Apparent latency fits every window's shift: each of the window's shown
  // samples (about one a field) at every shift of the search grid (2 ms
  // apart over ±max_shift, and about 20 more around the best).
  if (p.apparent_latency && p.apparent_latency->step > des::Time::zero()) {
    const measurement::ApparentLatencyParams& a = *p.apparent_latency;
    const double windows_per_s = 1.0 / a.step.to_seconds();
    const double samples = std::max(2.0, a.window.to_seconds() * fields_per_s);
    const double shifts = 2.0 * std::ceil(a.max_shift.to_ms() / 2.0) + 1.0 + 20.0;
    const double objects = p.controller ? 2.0 : 1.0;
    rates.push_back({"/apparent_latency/step_ms", "apparent_latency", objects * windows_per_s * samples * shifts, true});
  }
  // The camera reads the display and the filmed object once a frame.
  if (p.measurement) rates.push_back({"/measurement/fps", "measurement", 2.0 / p.measurement->frame_period.to_seconds(), true});
}

}  // namespace

std::vector<EventRate> shared_event_rates(const sections::SharedParams& p) {
  std::vector<EventRate> rates;
  // An IMU chain sends a report (an event) every report_every readings.
  const int head_step = p.tracker.imu ? p.tracker.imu->report_every : 1;
  const double tracker_hz = 1.0 / p.tracker.period.to_seconds() / head_step;
  rates.push_back({"/tracker/rate_hz", "tracker", tracker_hz});
  if (p.controller && p.controller->tracker) {
    const tracker::TrackerParams& c = *p.controller->tracker;
    const int step = c.imu ? c.imu->report_every : 1;
    rates.push_back({"/controller/tracker/rate_hz", "controller", 1.0 / c.period.to_seconds() / step});
  }
  // A busy serial line frees itself with one event per waiting record at most.
  if (p.transport.type == tracker::TransportParams::Type::Serial)
    rates.push_back({"/tracker/rate_hz", "transport", tracker_hz});
  const display::RasterParams& raster = p.display.raster;
  const double fields_per_s = 1.0 / raster.field_period.to_seconds();
  rates.push_back({"/display/refresh_hz", "display", fields_per_s});
  // Line scanout and batched pixel scanout: one event per active line;
  // pixel events: one per pixel_stride pixels of every active line.
  const double lines = raster.interlaced ? raster.height_px / 2 : raster.height_px;
  const double units = std::ceil(static_cast<double>(raster.width_px) / std::max(1, p.display.pixel_stride));
  if (p.display.fidelity == display::ScanoutFidelity::Line)
    rates.push_back({"/display/scanout", "display", lines * fields_per_s});
  if (p.display.fidelity == display::ScanoutFidelity::Pixel)
    rates.push_back(p.display.pixel_events ? EventRate{"/display/pixel_stride", "display", lines * units * fields_per_s}
                                           : EventRate{"/display/scanout", "display", lines * fields_per_s});
  add_measurement_rates(p, fields_per_s, rates);
  return rates;
}

}  // namespace latsim::pipelines
