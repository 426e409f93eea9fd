#include "latsim/results/seen_figures.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace latsim::results {

void SeenFigures::measure_apparent_latency(const measurement::ApparentLatencyParams& params,
                                               const tracker::MotionPhaseParams& phases) {
  apparent_ = params;
  apparent_phases_ = phases;
  keep_centre_trace();
}

void SeenFigures::keep_centre_trace() {
  if (centre_trace_) return;
  centre_trace_.emplace(measurement::ScreenPoint{0.5, 0.5}, timing_.params().width_px, timing_.lines_per_field());
  ++traces_;
}

void SeenFigures::film(const measurement::CameraRigParams& params, const des::PeriodicSchedule& camera) {
  rig_ = params;
  camera_ = camera;
  rig_trace_.emplace(params.display_point, timing_.params().width_px, timing_.lines_per_field());
  ++traces_;
}

void SeenFigures::track_controller(const tracker::MotionSource& motion) {
  controller_ = &motion;
  keep_centre_trace();
}

void SeenFigures::shown(const display::ScanoutSpan& span, const glm::dquat& orientation,
                                       const ImageRecord& img) {
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
    measurement::ShownSample s{des::Time::ps(span.photons.at(i)), span.lit_duration, orientation};
    s.written = des::Time::ps(span.written.at(i));
    if (controller_ != nullptr && img.controller_pose) {
      s.controller_drawn = true;
      s.controller = measurement::controller_seen(motion_.pose_at(s.photon).orientation, orientation,
                                                  img.controller_pose->orientation);
      s.controller_measured = img.controller_measured_at;
    }
    t.add(s);
  }
}

namespace {

// The controller's samples of a trace, as the shown orientation.
std::vector<measurement::ShownSample> controller_samples(std::span<const measurement::ShownSample> shown) {
  std::vector<measurement::ShownSample> out;
  out.reserve(shown.size());
  for (const measurement::ShownSample& s : shown) {
    if (!s.controller_drawn) continue;
    measurement::ShownSample c{s.photon, s.lit, s.controller};
    c.written = s.written;
    out.push_back(c);
  }
  return out;
}

}  // namespace

void SeenFigures::apparent_figures(const std::string& prefix, std::span<const measurement::ShownSample> shown,
                                       const tracker::MotionSource& truth) {
  tracker::MotionPhaseClassifier phases(truth, apparent_phases_);
  const measurement::ApparentLatencyResult r = measurement::apparent_latency(shown, truth, phases, *apparent_);
  for (const measurement::WindowShift& w : r.windows) {
    figures_.add(prefix + "apparent_latency_ms", w.shift_ms);
    figures_.add(prefix + "apparent_latency_ms_" + std::string(tracker::phase_name(w.phase)), w.shift_ms);
  }
  figures_.set(prefix + "apparent_latency_windows_unresolved", r.unresolved);
  for (double d : r.start_ms) figures_.add(prefix + "apparent_latency_ms_start", d);
  if (r.steady_ms) {
    for (double c : r.catch_up_ms) figures_.add(prefix + "prediction_catch_up_ms", c);
    figures_.set(prefix + "prediction_never_caught_up", r.never_caught_up);
  }
}

void SeenFigures::rig_figures(std::span<const measurement::ShownSample> shown, const tracker::MotionSource& truth,
                                  des::Time duration) {
  const glm::dquat reference = truth.pose_at(des::Time::zero()).orientation;
  const glm::dvec3 axis = rig_.axis;
  const measurement::ObjectSignal object([&truth, reference, axis](des::Time t) {
    return measurement::twist_deg(reference, truth.pose_at(t).orientation, axis);
  });
  // What the camera sees of each new value: the panel's transition (none
  // without persistence, where a pixel is an impulse).
  measurement::PanelRise rise;
  if (persistence_ != nullptr) {
    const display::PersistenceParams& pp = persistence_->params();
    rise.response = pp.response;
    rise.curve = pp.rise == display::PersistenceParams::Rise::linear        ? measurement::PanelRise::Curve::linear
                 : pp.rise == display::PersistenceParams::Rise::exponential ? measurement::PanelRise::Curve::exponential
                                                                             : measurement::PanelRise::Curve::step;
  }
  std::vector<measurement::LitAngle> lit = measurement::lit_angles(shown, reference, axis);
  if (rig_.display_signal == measurement::CameraRigParams::DisplaySignalKind::motion_flag) {
    const double threshold = rig_.flag_threshold_deg.value_or(
        measurement::calibrated_flag_threshold(lit, rig_.calibration, rig_.calibration_factor));
    figures_.set("measurement_flag_threshold_deg", threshold);
    lit = measurement::motion_flags(lit, threshold, rig_.flag_frames_behind);
  }
  const measurement::DisplaySignal display(std::move(lit), rise);
  const des::Time exposure = rig_.exposure ? *rig_.exposure : camera_.nominal_period();
  const measurement::RigResult r = measurement::film(object, display, camera_, exposure, duration, rig_);
  for (double v : r.frame_counting_ms) figures_.add("measured_latency_ms", v);
  // A motion flag has no trajectory to shift onto the object's.
  if (rig_.display_signal == measurement::CameraRigParams::DisplaySignalKind::angle)
    for (double v : r.shift_ms) figures_.add("measured_latency_shift_ms", v);
  figures_.set("measurement_resolution_ms", r.resolution_ms);
  figures_.set("measurement_movements", static_cast<int64_t>(r.frame_counting_ms.size()));
  figures_.set("measurement_frames", r.frames);
  if (r.frame_counting_ms.empty()) {
    const bool head = rig_.object == measurement::CameraRigParams::Object::head;
    figures_.warn(std::string("the camera rig saw no movement from rest to rest (measurement_movements is 0): the ") +
         (head ? "head" : "controller") +
         " must rest for /measurement/rest_ms between movements larger than /measurement/threshold_deg");
  }
}

void SeenFigures::finish(des::Time duration) {
  // Each trace sorted once (an empty span: no trace kept).
  using Samples = std::span<const measurement::ShownSample>;
  const Samples centre = centre_trace_ ? Samples(centre_trace_->sorted()) : Samples();
  const Samples rig = rig_trace_ ? Samples(rig_trace_->sorted()) : Samples();
  if ((centre_trace_ && centre.empty()) || (rig_trace_ && rig.empty()))
    figures_.warn("apparent latency, the camera rig and the controller's figures need whole images at the display point; "
         "this run lit none there (frameless rendering shows no images), so their figures are absent");
  if (!centre.empty()) {
    if (apparent_) apparent_figures("", centre, motion_);
    if (controller_ != nullptr) {
      for (const measurement::ShownSample& s : centre)
        if (s.controller_drawn) figures_.add("controller_latency_ms", (s.photon - s.controller_measured).to_ms());
      if (apparent_) apparent_figures("controller_", controller_samples(centre), *controller_);
    }
  }
  if (!rig.empty()) {
    if (rig_.object == measurement::CameraRigParams::Object::controller && controller_ != nullptr)
      rig_figures(controller_samples(rig), *controller_, duration);
    else
      rig_figures(rig, motion_, duration);
  }
}

}  // namespace latsim::results
