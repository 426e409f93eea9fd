#include "latsim/results/latency_recorder.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "latsim/results/frame_recorder.hpp"
#include "latsim/results/timeline.hpp"
#include "latsim/units/units.hpp"

namespace latsim::results {

namespace {


}  // namespace

LatencyRecorder::LatencyRecorder(const des::Simulator& sim, const tracker::MotionSource& motion, const tracker::HostFeed& host,
                                 ImageBook& images, const display::RasterTiming& timing, ProbeSet probes, double ipd_m,
                                 bool stereo, bool keep_samples)
    : sim_(sim),
      motion_(motion),
      host_(host),
      images_(images),
      timing_(timing),
      probes_(std::move(probes)),
      ipd_m_(ipd_m),
      stereo_(stereo),
      keep_samples_(keep_samples) {
  const double w = timing_.params().width_px, h = timing_.params().height_px;
  tan_half_h_ = std::tan(units::deg_to_rad(0.5 * probes_.hfov_deg));
  tan_half_v_ = tan_half_h_ * h / w;
  // Pixels per radian at the image centre of a pinhole display.
  rad_per_px_ = 2.0 * tan_half_h_ / w;
}

void LatencyRecorder::image_due(des::Time due_by) {
  deadlines_ = true;
  due_.push_back(due_by);
}

void LatencyRecorder::record(stats::Distribution*& d, const char* name, double value) {
  if (!d) d = &dists_.try_emplace(name, 0.005, keep_samples_).first->second;
  d->add(value);
  if (sample_log_.on()) sample_log_.add(sim_.now().to_ms(), name, value);
}

void LatencyRecorder::record(stats::Distribution*& d, const char* name, des::Time value) {
  if (!d) d = &dists_.try_emplace(name, 0.005, keep_samples_).first->second;
  runs_.close(d);  // a span figure's gathered run goes first
  d->add(value);
  if (sample_log_.on()) sample_log_.add(sim_.now().to_ms(), name, value.to_ms());
}

stats::Distribution& LatencyRecorder::figure(stats::Distribution*& d, const char* name) {
  if (!d) d = &dists_.try_emplace(name, 0.005, keep_samples_).first->second;
  return *d;
}

void LatencyRecorder::record_spans(const display::ScanoutSpan& span, des::Time orientation_measured,
                                   des::Time position_measured) {
  const des::Time origin = std::min(orientation_measured, position_measured);
  if (span.field != scan_field_) {
    scan_field_ = span.field;
    scan_start_ = timing_.scanout_start(span.field);
  }
  if (display_ms_ == nullptr || mtp_ == nullptr || rotation_ == nullptr || translation_ == nullptr) [[unlikely]] {
    figure(mtp_, "motion_to_photon_ms");
    figure(rotation_, "rotation_latency_ms");
    figure(translation_, "translation_latency_ms");
    figure(display_ms_, "display_ms");
  }
  // One open run per eye; each line of a field continues it at line fidelity.
  hot_[static_cast<size_t>(span.eye & 1)].valid = false;  // until on_scanout() knows the targets again
  runs_.add(static_cast<size_t>(span.eye & 1), span.photons,
            {{mtp_, origin.ticks()},
             {rotation_, orientation_measured.ticks()},
             {translation_, position_measured.ticks()},
             {display_ms_, scan_start_.ticks()}});
  if (!sample_log_.on()) return;
  log_run("motion_to_photon_ms", span, origin);
  log_run("rotation_latency_ms", span, orientation_measured);
  log_run("translation_latency_ms", span, position_measured);
  log_run("display_ms", span, scan_start_);
}

void LatencyRecorder::log_run(const char* name, const display::ScanoutSpan& span, des::Time origin) {
  stats::TickStepper photon(span.photons), written(span.written);
  for (uint64_t i = 0; i < span.photons.count; ++i, photon.step(), written.step())
    sample_log_.add(std::min(written.time(), sim_.now()).to_ms(), name, (photon.time() - origin).to_ms());
}

void LatencyRecorder::prune(int64_t below_id) {
  images_.prune(below_id);
  for (HotSpan& hot : hot_)
    if (hot.image_id < below_id) hot.valid = false;
}

void LatencyRecorder::on_field_start(int eye, int64_t field, des::Time retrace) {
  if (eye != 0) return;
  // Every sample measured before this retrace has been simulated: spans of
  // the last field that wait for the newest orientation can be completed.
  flush_pending();
  close_field();
  if (fields_count_ == nullptr) fields_count_ = &counters_["fields"];
  *fields_count_ += 1;
  open_field_ = field;
  open_retrace_ = retrace;
  new_in_open_field_ = false;
}

// Decides whether the field just scanned missed a refresh deadline.
void LatencyRecorder::close_field() {
  if (open_field_ == INT64_MIN) return;
  if (new_in_open_field_) {
    if (!due_.empty()) due_.pop_front();
  } else if (!due_.empty() && due_.front() <= open_retrace_) {
    ++missed_;
  }
}

void LatencyRecorder::on_scanout(const display::ScanoutSpan& span) {
  // At line fidelity nearly every span is the next line of the image and
  // field this eye's last span showed: it continues the open run, with the
  // same targets, and usually lights no probe.
  const size_t slot = static_cast<size_t>(span.eye & 1);
  const HotSpan& hot = hot_[slot];
  if (hot.valid && hot.image_id == span.image_id && hot.field == span.field && runs_.extend_run(slot, span.photons))
      [[likely]] {
    if (!probes_.points_m.empty() && !no_probe_on(span)) {
      const ImageRecord& img = images_.held(span.image_id)->record;  // prune() drops a pruned image's hot span
      record_probes(span, img.eye_pose.orientation, img.eye_pose.position_m, img.sample.index, span.image_id, true);
    }
    if (shown_traces_ != 0) [[unlikely]] {
      const ImageRecord& img = images_.held(span.image_id)->record;
      offer_shown(span, img.eye_pose.orientation, img);
    }
    return;
  }
  ImageBook::Held* shown = images_.held(span.image_id);
  if (shown == nullptr) {
    // One per sample, however the display groups samples into spans.
    counters_["unlit_spans"] += static_cast<int64_t>(span.photons.count);
    return;
  }
  const ImageRecord& img = shown->record;  // prune() below keeps the image shown now
  if (!shown->shown) {
    shown->shown = true;
    first_shown(img, span);
    // Images older than one shown now (same eye) will not be shown again
    // (erasing them leaves this one where it is).
    prune(span.image_id - 64);
  }
  if (ledger_.on()) ledger_.span(span.image_id, img, span, timing_);
  // At field fidelity every line is handled at the retrace, before the
  // samples measured during the field exist; an address recalculation image
  // takes its orientation from the newest sample when each line is fetched
  // (written), so such lines wait for the next retrace: the same rule at
  // every fidelity.
  if (img.orientation_at_scanout && des::Time::ps(span.written.last()) > sim_.now()) {
    const uint64_t written_by_now = span.written.first_index_at_or_above(sim_.now().ticks() + 1);
    if (written_by_now > 0) record_span(img, samples_of(span, 0, written_by_now));
    pending_.push_back(Pending{img, samples_of(span, written_by_now, span.written.count - written_by_now)});
    return;
  }
  if (!img.orientation_at_scanout) [[likely]] {
    record_image_pose(img, span);
    // The next span of this image and field continues this one's run (its
    // ledger row and logged samples need the whole path).
    if (!ledger_.on() && !sample_log_.on()) hot_[slot] = HotSpan{span.image_id, span.field, true};
    return;
  }
  record_span(img, span);
}

display::ScanoutSpan LatencyRecorder::samples_of(const display::ScanoutSpan& span, uint64_t begin,
                                                uint64_t n) const {
  if (begin == 0 && n == span.written.count) return span;
  display::ScanoutSpan part = span;
  if (span.line_end - span.line > 1) {
    // Several lines (field fidelity): one sample per line.
    part.line = span.line + static_cast<int>(begin);
    part.line_end = part.line + static_cast<int>(n);
    part.row = timing_.row_of(span.field, part.line);
  } else {
    // One line of batched pixels: one sample per x_step columns, the last
    // one cut at the span's end.
    part.x_begin = span.x_begin + static_cast<int>(begin) * span.x_step;
    part.x_end = begin + n == span.written.count ? span.x_end : part.x_begin + static_cast<int>(n) * span.x_step;
  }
  part.written = span.written.slice(begin, n);
  part.photons = span.photons.slice(begin, n);
  part.written_at = des::Time::ps(part.written.base);
  part.photon_time = des::Time::ps(part.photons.base);
  return part;
}

void LatencyRecorder::flush_pending() {
  for (const Pending& p : pending_) record_span(p.record, p.span);
  pending_.clear();
}

void LatencyRecorder::record_span(const ImageRecord& img, const display::ScanoutSpan& span) {
  if (!img.orientation_at_scanout) {
    record_image_pose(img, span);
    return;
  }
  // Address recalculation looks up the newest orientation as each pixel is
  // fetched (written), predicted by the host to the pixel's photon time. A
  // span of several samples goes in pieces that share that pose.
  const uint64_t n = span.written.count;
  const bool predicts = predicting_ || host_.predicts();
  if (n == 1 || (!predicts && span.line_end - span.line == 1)) {
    // One sample, or one line of batched pixels that the display cuts
    // wherever a sample arrives.
    record_uniform(img, span, host_.pose_for(span.written_at, span.photon_time));
    return;
  }
  if (predicts) {
    // Each sample has a pose of its own, predicted for its own photon time.
    for (uint64_t i = 0; i < n; ++i) {
      const display::ScanoutSpan one = samples_of(span, i, 1);
      record_uniform(img, one, host_.pose_for(one.written_at, one.photon_time));
    }
    return;
  }
  // Several lines (field fidelity): runs of lines that share the newest sample.
  uint64_t begin = 0;
  auto pose = host_.pose_for(span.written_at, span.photon_time);
  for (uint64_t i = 1; i <= n; ++i) {
    std::optional<tracker::PosePrediction> next;
    if (i < n) {
      next = host_.pose_for(des::Time::ps(span.written.at(i)), des::Time::ps(span.photons.at(i)));
      if (next.has_value() == pose.has_value() && (!next || next->sample.index == pose->sample.index)) continue;
    }
    record_uniform(img, samples_of(span, begin, i - begin), pose);
    pose = next;
    begin = i;
  }
}

void LatencyRecorder::record_uniform(const ImageRecord& img, const display::ScanoutSpan& span,
                                     const std::optional<tracker::PosePrediction>& newest) {
  if (!newest) {
    record_image_pose(img, span);
    return;
  }
  const glm::dquat orientation = tracker::eye_pose(newest->pose, span.eye, ipd_m_, stereo_).orientation;
  if (predicting_ && span.eye == 0 && span.line == timing_.lines_per_field() / 2 && span.x_begin == 0)
    add_prediction_error(*newest, true, false);
  const des::Time orientation_measured = newest->sample.measured_at;
  const des::Time position_measured = img.sample.measured_at;
  offer_shown(span, orientation, img);
  record_spans(span, orientation_measured, position_measured);
  // The age of the shown image's pose as the field starts to light up.
  if (span.line == 0 && span.x_begin == 0)
    record(image_age_, "image_age_ms", span.photon_time - std::min(orientation_measured, position_measured));
  if (!probes_.points_m.empty())
    record_probes(span, orientation, img.eye_pose.position_m, newest->sample.index, span.image_id, false);
}

void LatencyRecorder::record_image_pose(const ImageRecord& img, const display::ScanoutSpan& span) {
  // Time warp re-projected the image to a newer orientation (eye_pose has
  // it); the position is the rendered one.
  const des::Time orientation_measured =
      !img.orientation_at_scanout && img.warp == ImageRecord::Warp::rotation ? img.orientation_measured_at
                                                                            : img.sample.measured_at;
  const des::Time position_measured = img.sample.measured_at;
  offer_shown(span, img.eye_pose.orientation, img);
  record_spans(span, orientation_measured, position_measured);
  if (span.line == 0 && span.x_begin == 0) [[unlikely]]
    record(image_age_, "image_age_ms", span.photon_time - std::min(orientation_measured, position_measured));
  if (probes_.points_m.empty() || no_probe_on(span)) return;
  record_probes(span, img.eye_pose.orientation, img.eye_pose.position_m, img.sample.index, span.image_id, true);
}

bool LatencyRecorder::no_probe_on(const display::ScanoutSpan& span) const {
  // Most spans (one line each at line fidelity) show no probe: with the
  // image's hits indexed by line, that takes two loads.
  const ProbeCache& cache = probe_cache_[span.eye & 1];
  return cache.image_pose && cache.image_id == span.image_id && cache.field == span.field &&
         !cache.first_hit.empty() && span.line >= 0 && span.line_end <= timing_.lines_per_field() &&
         cache.first_hit[static_cast<size_t>(span.line)] == cache.first_hit[static_cast<size_t>(span.line_end)];
}

void LatencyRecorder::first_shown(const ImageRecord& img, const display::ScanoutSpan& span) {
  // Rendering latency ends where the result starts to be scanned out: when
  // the first span that shows it is written (line 0 of the field for an image
  // swapped in at a retrace, the line being scanned for one shown at once
  // (tearing) or written just ahead of the beam (a strip)).
  const double render_latency_ms = (span.written_at - img.render_start).to_ms();
  record(render_latency_, "render_latency_ms", render_latency_ms);
  record(render_latency_fields_, "render_latency_fields", render_latency_ms / timing_.field_period_ms());
  record(tracker_to_render_, "tracker_to_render_ms", (img.render_start - img.sample.measured_at).to_ms());
  // A later strip of a refresh's image has its own latency but is not
  // another image in the frame rate.
  if (!img.continues_image) {
    if (images_shown_count_ == nullptr) images_shown_count_ = &counters_["images_shown"];
    *images_shown_count_ += 1;
  }
  if (span.eye == 0) {
    if (!img.continues_image) ++first_shown_eye0_;
    if (span.field == open_field_) new_in_open_field_ = true;
    if (timeline_ && img.render_start > img.host_received)
      timeline_->add("HOST", img.frame, -1, "host application", img.host_received, img.render_start);
    // The causal chain of a new image: its pose sample, its first photon,
    // and the latency between them as a counter track.
    if (timeline_ && !img.continues_image) {
      timeline_->add_flow(span.image_id, "pose samples", img.sample.measured_at, "photons", span.photon_time);
      timeline_->add_counter("motion_to_photon_ms", span.photon_time,
                             (span.photon_time - img.sample.measured_at).to_ms());
    }
  }
  // Once per image (stereo pairs share one head pose): what it was predicted
  // from, for when, and how far off. Address recalculation replaces the
  // orientation at scanout, so only its position counts here. A rotation
  // warp's prediction is the warp's own: its orientation, from the warp's
  // sample to the warp's target (the position it keeps was predicted by the
  // application for another instant, and is not judged here).
  if (predicting_ && img.eye == 0) {
    tracker::PosePrediction p{img.sample, img.predicted_for, img.head_pose};
    const bool rotation_warp = img.warp == ImageRecord::Warp::rotation;
    if (rotation_warp) p.sample.measured_at = img.orientation_measured_at;
    add_prediction_error(p, !img.orientation_at_scanout, !rotation_warp);
  }
  if (ledger_.on()) ledger_.image_shown(span.image_id, img, span, timing_);
  if (app_frames_ && img.shows_app_frame) app_frames_->shown(img.frame, span.photon_time);
}

void LatencyRecorder::pixel_lit(const tracker::TrackerSample& s, des::Time photon) {
  const des::Time age = photon - s.measured_at;
  record(mtp_, "motion_to_photon_ms", age);
  record(rotation_, "rotation_latency_ms", age);
  record(translation_, "translation_latency_ms", age);
  record(pixel_age_, "pixel_age_ms", age);
}

void LatencyRecorder::pixel_age(const tracker::TrackerSample& s, des::Time photon) {
  record(pixel_age_, "pixel_age_ms", photon - s.measured_at);
}

void LatencyRecorder::record_carried(const tracker::TrackerSample& s, const tracker::Carriage& c, bool line) {
  ++records_offered_;
  record(tracker_to_host_, "tracker_to_host_ms", (c.visible - s.measured_at).to_ms());
  if (line) record(line_wait_, "line_wait_ms", (c.start - s.ready_at).to_ms());
  if (ledger_.on()) ledger_.carried(s, c);
}

void LatencyRecorder::enable_prediction(bool on) { predicting_ = on; }

void LatencyRecorder::split_by_phase(const tracker::MotionPhaseParams& params) {
  phases_.emplace(motion_, params);
}

void LatencyRecorder::add_split(PhaseSplit& split, const char* name, double value, des::Time at) {
  if (!phases_) return;
  const tracker::MotionPhase phase = phases_->phase_at(at);
  const auto i = static_cast<size_t>(phase);
  const std::string split_name = std::string(name) + "_" + std::string(tracker::phase_name(phase));
  record(split[i], split_name.c_str(), value);
}

void LatencyRecorder::add_prediction_error(const tracker::PosePrediction& p, bool orientation, bool position) {
  const tracker::Pose truth = motion_.pose_at(p.target);
  record(prediction_horizon_, "prediction_horizon_ms", p.horizon().to_ms());
  if (orientation) {
    const double deg = units::rad_to_deg(tracker::angle_between(p.pose.orientation, truth.orientation));
    record(prediction_deg_, "prediction_error_deg", deg);
    add_split(prediction_split_, "prediction_error_deg", deg, p.target);
  }
  if (position) record(prediction_mm_, "prediction_error_mm", glm::length(p.pose.position_m - truth.position_m) * 1e3);
}

}  // namespace latsim::results
