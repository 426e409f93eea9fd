// The span latencies: per lit span, how old the pose it shows is.
#pragma once

#include <cstdint>

#include "latsim/des/simulator.hpp"
#include "latsim/display/display.hpp"
#include "latsim/display/raster_timing.hpp"
#include "latsim/results/figure_writer.hpp"
#include "latsim/stats/run_feed.hpp"
#include "latsim/stats/stats.hpp"
#include "latsim/tracker/tracker.hpp"

namespace latsim::results {

/// Turns every lit span into motion_to_photon_ms, rotation_latency_ms,
/// translation_latency_ms and display_ms (each sample's photon time minus
/// its origins, in closed form for a run of samples), the first line of a
/// field into image_age_ms, and a frameless pixel into its latencies and
/// pixel_age_ms. A span that continues its eye's open run (the next line of
/// the image and field the eye's last span showed) extends that run.
class SpanLatencies {
 public:
  SpanLatencies(FigureWriter figures, const des::Simulator& sim, const display::RasterTiming& timing)
      : figures_(std::move(figures)), sim_(sim), timing_(timing) {}
  SpanLatencies(const SpanLatencies&) = delete;
  SpanLatencies& operator=(const SpanLatencies&) = delete;

  /// Every sample of `span`: photon time minus the older of the origins,
  /// minus each origin, and minus the start of the field's scanout.
  void record(const display::ScanoutSpan& span, des::Time orientation_measured, des::Time position_measured);
  /// image_age_ms of the span that opens a field's image (its line 0, column 0).
  void image_age(des::Time photon, des::Time origin) { add(image_age_, "image_age_ms", photon - origin); }
  /// A pixel lit at `photon` with a colour computed wholly from sample `s`:
  /// motion-to-photon, rotation, translation and pixel age alike.
  void pixel_lit(const tracker::TrackerSample& s, des::Time photon);
  /// Age of a sampled pixel of a whole image computed from `s`.
  void pixel_age(const tracker::TrackerSample& s, des::Time photon) {
    add(pixel_age_, "pixel_age_ms", photon - s.measured_at);
  }

  /// Whether `span` continues the open run of its eye, the last span of the
  /// same image and field held with hold(); if so it is added to that run.
  bool extend(const display::ScanoutSpan& span) {
    const size_t slot = static_cast<size_t>(span.eye & 1);
    const Hot& hot = hot_[slot];
    return hot.valid && hot.image_id == span.image_id && hot.field == span.field && runs_.extend_run(slot, span.photons);
  }
  /// The span just recorded with its image's own pose: the next span of that
  /// image and field on its eye may extend its run.
  void hold(const display::ScanoutSpan& span) { hot_[static_cast<size_t>(span.eye & 1)] = Hot{span.image_id, span.field, true}; }
  /// Spans of images below `image_id` are no longer held.
  void release_below(int64_t image_id) {
    for (Hot& hot : hot_)
      if (hot.image_id < image_id) hot.valid = false;
  }
  void release_all() { hot_[0].valid = hot_[1].valid = false; }
  /// Adds every gathered run (before the distributions are read).
  void complete() const { runs_.close_all(); }

 private:
  struct Hot {
    int64_t image_id = -1;
    int64_t field = INT64_MIN;
    bool valid = false;
  };

  /// A duration, kept exactly; the distribution's gathered run goes first.
  void add(stats::Distribution*& d, const char* name, des::Time value);
  stats::Distribution& figure(stats::Distribution*& d, const char* name) {
    if (!d) d = &figures_.distribution(name);
    return *d;
  }
  /// The samples of a span for samples.csv, logged at each sample's write, or
  /// now when that is earlier (a field computed ahead at its retrace), as the
  /// per-sample events would.
  void log_run(const char* name, const display::ScanoutSpan& span, des::Time origin);

  FigureWriter figures_;
  const des::Simulator& sim_;
  const display::RasterTiming& timing_;
  stats::Distribution* mtp_ = nullptr;
  stats::Distribution* rotation_ = nullptr;
  stats::Distribution* translation_ = nullptr;
  stats::Distribution* display_ms_ = nullptr;
  stats::Distribution* image_age_ = nullptr;
  stats::Distribution* pixel_age_ = nullptr;
  int64_t scan_field_ = INT64_MIN;  // field whose scanout start is cached
  des::Time scan_start_;
  // Per eye: the image and field of the last span held, while the run it was
  // added to is the eye's open run with that span's targets (record() clears
  // it before any other add).
  Hot hot_[2];
  // The runs of the span figures, gathered across spans; closed whenever the
  // figures are read, so they are always complete (hence mutable).
  mutable stats::RunFeed runs_;
};

}  // namespace latsim::results
