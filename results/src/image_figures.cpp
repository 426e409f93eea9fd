#include "latsim/results/image_figures.hpp"

#include <cstdio>
#include <string>

#include "latsim/results/timeline.hpp"

#include "fixed_text.hpp"

namespace latsim::results {

void ImageFigures::field_started(int64_t field, des::Time retrace) {
  close_field();
  open_field_ = field;
  open_retrace_ = retrace;
  new_in_open_field_ = false;
}

// Decides whether the field just scanned missed a refresh deadline.
void ImageFigures::close_field() {
  if (open_field_ == INT64_MIN) return;
  if (new_in_open_field_) {
    if (!due_.empty()) due_.pop_front();
  } else if (!due_.empty() && due_.front() <= open_retrace_) {
    ++missed_;
  }
}

void ImageFigures::first_shown(int64_t image_id, const ImageRecord& img, const display::ScanoutSpan& span) {
  // Rendering latency ends where the result starts to be scanned out: when
  // the first span that shows it is written (line 0 of the field for an image
  // swapped in at a retrace, the line being scanned for one shown at once
  // (tearing) or written just ahead of the beam (a strip)).
  const double render_latency_ms = (span.written_at - img.render_start).to_ms();
  figures_.add(render_latency_, "render_latency_ms", render_latency_ms);
  figures_.add(render_latency_fields_, "render_latency_fields", render_latency_ms / timing_.field_period_ms());
  figures_.add(tracker_to_render_, "tracker_to_render_ms", (img.render_start - img.sample.measured_at).to_ms());
  // A later strip of a refresh's image has its own latency but is not
  // another image in the frame rate.
  if (!img.continues_image) {
    if (images_shown_ == nullptr) images_shown_ = &figures_.counter("images_shown");
    *images_shown_ += 1;
  }
  if (span.eye != 0) return;
  if (!img.continues_image) ++first_shown_eye0_;
  if (span.field == open_field_) new_in_open_field_ = true;
  if (timeline_ && img.render_start > img.host_received)
    timeline_->add("HOST", img.frame, -1, "host application", img.host_received, img.render_start);
  // The causal chain of a new image: its pose sample, its first photon, and
  // the latency between them as a counter track.
  if (timeline_ && !img.continues_image) {
    timeline_->add_flow(image_id, "pose samples", img.sample.measured_at, "photons", span.photon_time);
    timeline_->add_counter("motion_to_photon_ms", span.photon_time, (span.photon_time - img.sample.measured_at).to_ms());
  }
}

void ImageFigures::finish(des::Time duration, int64_t images_registered) {
  // A field whose first line would be lit after the run showed nothing, new
  // or old: there is nothing to judge it by.
  if (open_field_ != INT64_MIN && timing_.scanout_start(open_field_) > duration) open_field_ = INT64_MIN;
  close_field();
  open_field_ = INT64_MIN;
  // A pipeline without whole images (frameless) has no frame rate.
  images_ = expects_images_ || deadlines_ || images_registered > 0;
  if (images_) figures_.set("frame_rate_hz", static_cast<double>(first_shown_eye0_) / duration.to_seconds());
  if (deadlines_) figures_.set("missed_refreshes", missed_);
}

void ImageFigures::warn(des::Time duration, int64_t fields) {
  if (images_ && first_shown_eye0_ == 0)
    figures_.warn("no image was shown in " + fixed(duration.to_seconds(), 3) +
                  " s of simulated time: rendering never finished");
  else if (missed_ > 0)
    figures_.warn(std::to_string(missed_) + " of " + std::to_string(fields) +
                  " refreshes showed no new image although one was due (missed_refreshes)");
}

}  // namespace latsim::results
