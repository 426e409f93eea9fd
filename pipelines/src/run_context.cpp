#include "latsim/pipelines/run_context.hpp"

#include "latsim/des/run_clocks.hpp"
#include "latsim/results/timeline.hpp"

namespace latsim::pipelines {

void RunContext::end_run_early(std::string why) {
  if (ended_early) return;
  ended_early = std::move(why);
  sim.stop();
}

const des::Clock& RunContext::clock(const std::string& name, const std::string& phase_pointer,
                                    des::RationalSeconds nominal, const des::ClockSettings& settings) const {
  return clocks.resolve(name, phase_pointer, nominal, settings);
}

tracker::Pose RunContext::eye_pose(const tracker::Pose& head, int eye) const {
  return tracker::eye_pose(head, eye, ipd_m, stereo);
}

results::ImageRecord RunContext::image_record(int64_t frame, int eye, const tracker::PosePrediction& p, des::Time start,
                                     des::Time end) const {
  results::ImageRecord rec;
  rec.frame = frame;
  rec.eye = eye;
  rec.sample = p.sample;
  rec.host_received = host.received_at(p.sample);
  rec.render_start = start;
  rec.render_end = end;
  rec.predicted_for = p.target;
  rec.head_pose = p.pose;
  rec.eye_pose = eye_pose(p.pose, eye);
  draw_controller(rec, p);
  return rec;
}

void RunContext::draw_controller(results::ImageRecord& rec, const tracker::PosePrediction& rendered) const {
  if (const std::optional<tracker::PosePrediction> c = host.controller_for(rendered)) {
    rec.controller_pose = c->pose;
    rec.controller_measured_at = c->sample.measured_at;
  }
}

void RunContext::present_display_memory(int64_t frame, const tracker::PosePrediction& p, des::Time start,
                                        const std::string& unit) {
  present_display_memory(frame, p, start, sim.now(), unit);
}

void RunContext::present_display_memory(int64_t frame, const tracker::PosePrediction& p, des::Time start, des::Time end,
                                        const std::string& unit) {
  for (int eye = 0; eye < display.eyes(); ++eye) {
    results::ImageRecord rec = image_record(frame, eye, p, start, end);
    rec.orientation_at_scanout = true;
    display.present_at_next_retrace(eye, images.add(rec));
  }
  if (timeline) timeline->add("RENDER", frame, -1, unit, start, end);
}

des::Time RunContext::photon_time(int64_t field, int line, int x) const {
  return display.persistence().lit(field, display.timing().pixel_time(field, line, x)).middle();
}

des::Time RunContext::frame_photon_time(int64_t field) const {
  return photon_time(field, display.timing().lines_per_field() / 2);
}

des::Time RunContext::photon_time_after(des::Time ready, int64_t later_fields) const {
  return frame_photon_time(display.timing().field_at_or_after(ready) + later_fields);
}

des::Time RunContext::first_line_photon_time(des::Time t) const {
  const display::RasterTiming& timing = display.timing();
  const int64_t field = timing.field_at_or_before(t);
  const int lines = timing.lines_per_field();
  // Line times grow with the line: the first one at or after t by bisection;
  // past the field's last line, the next field's first.
  if (timing.line_time(field, lines - 1) < t) return photon_time(field + 1, 0);
  int lo = 0, hi = lines - 1;
  while (lo < hi) {
    const int mid = lo + (hi - lo) / 2;
    if (timing.line_time(field, mid) >= t) hi = mid;
    else lo = mid + 1;
  }
  return photon_time(field, lo);
}

void RunContext::fetch_orientation_at_scanout() {
  if (!display.batches_pixels()) return;
  host.on_delivery([d = &display](const tracker::TrackerSample&, des::Time) { d->split_scanout(); });
}

}  // namespace latsim::pipelines
