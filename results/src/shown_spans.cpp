#include "latsim/results/shown_spans.hpp"

#include <algorithm>

#include "latsim/results/frame_recorder.hpp"
#include "latsim/tracker/pose.hpp"

namespace latsim::results {

ShownSpans::ShownSpans(FigureWriter figures, const des::Simulator& sim, const tracker::HostFeed& host,
                       ImageBook& images, const display::RasterTiming& timing, SpanListeners listeners, double ipd_m,
                       bool stereo)
    : figures_(std::move(figures)),
      sim_(sim),
      host_(host),
      images_(images),
      timing_(timing),
      listeners_(listeners),
      ipd_m_(ipd_m),
      stereo_(stereo) {}

void ShownSpans::prune(int64_t below_id) {
  images_.prune(below_id);
  listeners_.latencies.release_below(below_id);
}

void ShownSpans::on_field_start(int eye, int64_t field, des::Time retrace) {
  if (eye != 0) return;
  // Every sample measured before this retrace has been simulated: spans of
  // the last field that wait for the newest orientation can be completed.
  flush();
  listeners_.images.field_started(field, retrace);
  if (fields_count_ == nullptr) fields_count_ = &figures_.counter("fields");
  *fields_count_ += 1;
}

void ShownSpans::on_scanout(const display::ScanoutSpan& span) {
  // At line fidelity nearly every span is the next line of the image and
  // field this eye's last span showed: it continues the open run, with the
  // same targets, and usually lights no probe.
  if (listeners_.latencies.extend(span)) [[likely]] {
    RegistrationErrors& registration = listeners_.registration;
    if (registration.has_probes() && !registration.no_probe_on(span)) {
      const ImageRecord& img = images_.held(span.image_id)->record;  // prune() releases a pruned image's span
      registration.probes_lit(span, img.eye_pose.orientation, img.eye_pose.position_m, img.sample.index, span.image_id,
                              true);
    }
    if (listeners_.seen.wants(span)) [[unlikely]] {
      const ImageRecord& img = images_.held(span.image_id)->record;
      listeners_.seen.shown(span, img.eye_pose.orientation, img);
    }
    return;
  }
  ImageBook::Held* shown = images_.held(span.image_id);
  if (shown == nullptr) {
    // One per sample, however the display groups samples into spans.
    figures_.count("unlit_spans", static_cast<int64_t>(span.photons.count));
    return;
  }
  const ImageRecord& img = shown->record;  // prune() below keeps the image shown now
  if (!shown->shown) {
    shown->shown = true;
    first_shown(span.image_id, img, span);
    // Images older than one shown now (same eye) will not be shown again
    // (erasing them leaves this one where it is).
    prune(span.image_id - 64);
  }
  if (listeners_.ledger.on()) listeners_.ledger.span(span.image_id, img, span, timing_);
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
    // The next span of this image and field continues this one's run.
    if (continuation_) listeners_.latencies.hold(span);
    return;
  }
  record_span(img, span);
}

display::ScanoutSpan ShownSpans::samples_of(const display::ScanoutSpan& span, uint64_t begin, uint64_t n) const {
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

void ShownSpans::flush() {
  for (const Pending& p : pending_) record_span(p.record, p.span);
  pending_.clear();
}

void ShownSpans::record_span(const ImageRecord& img, const display::ScanoutSpan& span) {
  if (!img.orientation_at_scanout) {
    record_image_pose(img, span);
    return;
  }
  // Address recalculation looks up the newest orientation as each pixel is
  // fetched (written), predicted by the host to the pixel's photon time. A
  // span of several samples goes in pieces that share that pose.
  const uint64_t n = span.written.count;
  const bool predicts = listeners_.prediction.on() || host_.predicts();
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

void ShownSpans::record_uniform(const ImageRecord& img, const display::ScanoutSpan& span,
                                const std::optional<tracker::PosePrediction>& newest) {
  if (!newest) {
    record_image_pose(img, span);
    return;
  }
  const glm::dquat orientation = tracker::eye_pose(newest->pose, span.eye, ipd_m_, stereo_).orientation;
  if (listeners_.prediction.on() && span.eye == 0 && span.line == timing_.lines_per_field() / 2 && span.x_begin == 0)
    listeners_.prediction.pose_predicted(*newest, true, false);
  const des::Time orientation_measured = newest->sample.measured_at;
  const des::Time position_measured = img.sample.measured_at;
  offer_shown(span, orientation, img);
  listeners_.latencies.record(span, orientation_measured, position_measured);
  // The age of the shown image's pose as the field starts to light up.
  if (span.line == 0 && span.x_begin == 0)
    listeners_.latencies.image_age(span.photon_time, std::min(orientation_measured, position_measured));
  if (listeners_.registration.has_probes())
    listeners_.registration.probes_lit(span, orientation, img.eye_pose.position_m, newest->sample.index,
                                       span.image_id, false);
}

void ShownSpans::record_image_pose(const ImageRecord& img, const display::ScanoutSpan& span) {
  // Time warp re-projected the image to a newer orientation (eye_pose has
  // it); the position is the rendered one.
  const des::Time orientation_measured =
      !img.orientation_at_scanout && img.warp == ImageRecord::Warp::rotation ? img.orientation_measured_at
                                                                            : img.sample.measured_at;
  const des::Time position_measured = img.sample.measured_at;
  offer_shown(span, img.eye_pose.orientation, img);
  listeners_.latencies.record(span, orientation_measured, position_measured);
  if (span.line == 0 && span.x_begin == 0) [[unlikely]]
    listeners_.latencies.image_age(span.photon_time, std::min(orientation_measured, position_measured));
  RegistrationErrors& registration = listeners_.registration;
  if (!registration.has_probes() || registration.no_probe_on(span)) return;
  registration.probes_lit(span, img.eye_pose.orientation, img.eye_pose.position_m, img.sample.index, span.image_id,
                          true);
}

void ShownSpans::first_shown(int64_t image_id, const ImageRecord& img, const display::ScanoutSpan& span) {
  listeners_.images.first_shown(image_id, img, span);
  listeners_.prediction.image_shown(img);
  if (listeners_.ledger.on()) listeners_.ledger.image_shown(image_id, img, span, timing_);
  if (app_frames_ && img.shows_app_frame) app_frames_->shown(img.frame, span.photon_time);
}

}  // namespace latsim::results
