// Per image first shown, and the refreshes that showed none although one
// was due.
#pragma once

#include <cstdint>
#include <deque>

#include "latsim/display/display.hpp"
#include "latsim/display/raster_timing.hpp"
#include "latsim/results/figure_writer.hpp"
#include "latsim/results/image_record.hpp"
#include "latsim/stats/stats.hpp"

namespace latsim::results {

class Timeline;

/// Turns the first span of every image into render_latency_ms,
/// render_latency_fields, tracker_to_render_ms and counts.images_shown, the
/// refreshes of eye 0 into frame_rate_hz and missed_refreshes, and logs each
/// new image's causal chain on the timeline.
class ImageFigures {
 public:
  ImageFigures(FigureWriter figures, const display::RasterTiming& timing)
      : figures_(std::move(figures)), timing_(timing) {}

  void set_timeline(Timeline* timeline) { timeline_ = timeline; }
  /// The pipeline shows whole images (it has a frame rate, and a run that
  /// shows none is warned about).
  void shows_images() { expects_images_ = true; }
  /// A render began that the pipeline means to show by the first refresh at
  /// or after `due_by`; every refresh from then on that shows no new image
  /// counts as missed until one is shown. A pipeline that never says so sets
  /// itself no refresh deadline and reports no missed_refreshes.
  void image_due(des::Time due_by) {
    deadlines_ = true;
    due_.push_back(due_by);
  }
  /// A retrace of eye 0: the field before it is judged.
  void field_started(int64_t field, des::Time retrace);
  /// The first span `span` showing image `image_id`.
  void first_shown(int64_t image_id, const ImageRecord& img, const display::ScanoutSpan& span);

  /// frame_rate_hz and missed_refreshes, once the run has ended at
  /// `duration` after `images_registered` images were registered.
  void finish(des::Time duration, int64_t images_registered);
  /// The warnings of a run that showed no image or missed refreshes.
  void warn(des::Time duration, int64_t fields);

 private:
  void close_field();

  FigureWriter figures_;
  const display::RasterTiming& timing_;
  Timeline* timeline_ = nullptr;
  stats::Distribution* render_latency_ = nullptr;
  stats::Distribution* render_latency_fields_ = nullptr;
  stats::Distribution* tracker_to_render_ = nullptr;
  int64_t* images_shown_ = nullptr;  // counts.images_shown once counted
  // Refresh deadlines: due times of renders not yet shown, oldest first, and
  // the field (one eye) being scanned now.
  std::deque<des::Time> due_;
  bool deadlines_ = false;
  bool expects_images_ = false;
  bool images_ = false;  // the run has whole images (decided at finish)
  int64_t open_field_ = INT64_MIN;
  des::Time open_retrace_;
  bool new_in_open_field_ = false;
  int64_t missed_ = 0;
  int64_t first_shown_eye0_ = 0;
};

}  // namespace latsim::results
