// What a viewer or a camera sees: the recorder's apparent latency and the
// simulated camera rig, computed at the end of the run from the orientation
// shown at one pixel per refresh.
#include <cmath>

#include "latsim/results/latency_recorder.hpp"

namespace latsim::results {

void LatencyRecorder::measure_apparent_latency(const measurement::ApparentLatencyParams& params,
                                               const tracker::MotionPhaseParams& phases) {
  apparent_ = params;
  apparent_phases_ = phases;
  centre_trace_.emplace(measurement::ScreenPoint{0.5, 0.5}, timing_.params().width_px, timing_.lines_per_field());
  ++shown_traces_;
}

void LatencyRecorder::film(const measurement::CameraRigParams& params, const des::PeriodicSchedule& camera) {
  rig_ = params;
  camera_ = camera;
  rig_trace_.emplace(params.display_point, timing_.params().width_px, timing_.lines_per_field());
  ++shown_traces_;
}

void LatencyRecorder::offer_shown_slow(const display::ScanoutSpan& span, const glm::dquat& orientation) {
  for (std::optional<measurement::ShownTrace>* trace : {&centre_trace_, &rig_trace_}) {
    if (!trace->has_value()) continue;
    measurement::ShownTrace& t = **trace;
    if (t.line() < span.line || t.line() >= span.line_end) continue;
    // One sample per line when the span covers several lines; otherwise one
    // per x_step columns of its line.
    uint64_t i = 0;
    if (span.line_end - span.line > 1) {
      i = static_cast<uint64_t>(t.line() - span.line);
    } else if (span.photons.count > 1) {
      if (t.column() < span.x_begin || t.column() >= span.x_end) continue;
      i = static_cast<uint64_t>((t.column() - span.x_begin) / std::max(1, span.x_step));
    } else if (span.x_end > span.x_begin && (t.column() < span.x_begin || t.column() >= span.x_end)) {
      continue;
    }
    if (i >= span.photons.count) continue;
    t.add(des::Time::ps(span.photons.at(i)), span.lit_duration, orientation);
  }
}

void LatencyRecorder::measurement_figures(des::Time duration) {
  if ((centre_trace_ && centre_trace_->sorted().empty()) || (rig_trace_ && rig_trace_->sorted().empty()))
    warn("apparent latency and the camera rig need whole images at the display point; this run lit none there "
         "(frameless rendering shows no images), so their figures are absent");
  if (centre_trace_ && !centre_trace_->sorted().empty()) {
    tracker::MotionPhaseClassifier phases(motion_, apparent_phases_);
    const measurement::ApparentLatencyResult r =
        measurement::apparent_latency(centre_trace_->sorted(), motion_, phases, apparent_);
    for (const measurement::WindowShift& w : r.windows) {
      add("apparent_latency_ms", w.shift_ms);
      add("apparent_latency_ms_" + std::string(tracker::phase_name(w.phase)), w.shift_ms);
    }
    table_.set("apparent_latency_windows_unresolved", r.unresolved);
    if (r.steady_ms) {
      for (double c : r.catch_up_ms) add("prediction_catch_up_ms", c);
      table_.set("prediction_never_caught_up", r.never_caught_up);
    }
  }
  if (rig_trace_ && !rig_trace_->sorted().empty()) {
    const glm::dquat reference = motion_.pose_at(des::Time::zero()).orientation;
    const glm::dvec3 axis = rig_.axis;
    const tracker::MotionSource& motion = motion_;
    const measurement::ObjectSignal object(
        [&motion, reference, axis](des::Time t) { return measurement::twist_deg(reference, motion.pose_at(t).orientation, axis); });
    const measurement::DisplaySignal display(measurement::lit_angles(rig_trace_->sorted(), reference, axis));
    const des::Time exposure = rig_.exposure ? *rig_.exposure : camera_.nominal_period();
    const measurement::RigResult r = measurement::film(object, display, camera_, exposure, duration, rig_);
    for (double v : r.frame_counting_ms) add("measured_latency_ms", v);
    for (double v : r.shift_ms) add("measured_latency_shift_ms", v);
    table_.set("measurement_resolution_ms", r.resolution_ms);
    table_.set("measurement_movements", static_cast<int64_t>(r.frame_counting_ms.size()));
    table_.set("measurement_frames", r.frames);
    if (r.frame_counting_ms.empty())
      warn("the camera rig saw no movement from rest to rest (measurement_movements is 0): the head must rest for "
           "/measurement/rest_ms between movements larger than /measurement/threshold_deg");
  }
}

}  // namespace latsim::results
