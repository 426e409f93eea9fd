#include "latsim/pipelines/event_rate.hpp"

#include <algorithm>
#include <cmath>

namespace latsim::pipelines {

double paced_per_s(des::Time period, double cap_hz) { return paced_per_s(period.to_seconds(), cap_hz); }

double paced_per_s(double period_s, double cap_hz) {
  if (period_s <= 0.0) return cap_hz;
  return std::min(cap_hz, 1.0 / period_s);
}

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
  // Motion phases classify the head's motion step by step up to every instant asked about.
  if (p.motion_phases && p.motion_phases->step > des::Time::zero())
    rates.push_back({"/motion_phases/step_ms", "motion_phases", 1.0 / p.motion_phases->step.to_seconds(), true});
  return rates;
}

}  // namespace latsim::pipelines
