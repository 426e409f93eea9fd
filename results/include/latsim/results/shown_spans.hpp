// What each scanned span shows, handed to the listeners of each figure family.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "latsim/des/simulator.hpp"
#include "latsim/display/display.hpp"
#include "latsim/display/raster_timing.hpp"
#include "latsim/results/figure_writer.hpp"
#include "latsim/results/image_book.hpp"
#include "latsim/results/image_figures.hpp"
#include "latsim/results/ledger.hpp"
#include "latsim/results/prediction_errors.hpp"
#include "latsim/results/registration_errors.hpp"
#include "latsim/results/seen_figures.hpp"
#include "latsim/results/span_latencies.hpp"
#include "latsim/tracker/host_feed.hpp"

namespace latsim::results {

class FrameRecorder;

/// The listeners a span is handed to, one per figure family.
struct SpanListeners {
  SpanLatencies& latencies;
  ImageFigures& images;
  RegistrationErrors& registration;
  PredictionErrors& prediction;
  SeenFigures& seen;
  Ledger& ledger;
};

/// Listens to the display: looks up the image every scanned span shows, the
/// orientation it shows (the image's own, a warp's, or for address
/// recalculation the newest sample when the span is written, predicted to
/// its photon time) and the instants that orientation and position were
/// measured, and hands the span to the listeners of each family: span
/// latencies, image figures on an image's first span, registration at the
/// probes it lights, prediction errors, the shown traces and the ledger.
/// Counts the retraces (counts.fields) and the samples that show no image
/// (counts.unlit_spans).
class ShownSpans : public display::ScanoutListener {
 public:
  ShownSpans(FigureWriter figures, const des::Simulator& sim, const tracker::HostFeed& host, ImageBook& images,
             const display::RasterTiming& timing, SpanListeners listeners, double ipd_m, bool stereo);

  /// Told the first photon of every image of an application frame (presentmon.csv).
  void set_frame_recorder(FrameRecorder* frames) { app_frames_ = frames; }
  /// A span continues the open run of its eye only without a ledger and a
  /// sample log (a ledger row and logged samples need every span's path).
  void set_continuation(bool on) {
    continuation_ = on;
    listeners_.latencies.release_all();
  }

  void on_field_start(int eye, int64_t field, des::Time retrace) override;
  void on_scanout(const display::ScanoutSpan& span) override;
  /// Completes the spans that wait for samples simulated after them.
  void flush();

 private:
  /// A span whose orientation must come from a sample not simulated yet.
  struct Pending {
    ImageRecord record;
    display::ScanoutSpan span;
  };

  void record_span(const ImageRecord& img, const display::ScanoutSpan& span);
  /// A span whose every sample shows one orientation: `newest` for an address
  /// recalculation image (none: no sample visible yet), else the image's.
  void record_uniform(const ImageRecord& img, const display::ScanoutSpan& span,
                      const std::optional<tracker::PosePrediction>& newest);
  /// record_uniform() with the orientation the image was drawn (or warped) to.
  void record_image_pose(const ImageRecord& img, const display::ScanoutSpan& span);
  /// Samples [begin, begin + n) of a span: lines at field fidelity, columns
  /// of one line at batched pixel fidelity.
  display::ScanoutSpan samples_of(const display::ScanoutSpan& span, uint64_t begin, uint64_t n) const;
  void first_shown(int64_t image_id, const ImageRecord& img, const display::ScanoutSpan& span);
  void prune(int64_t below_id);
  /// Hands the orientation a span of eye 0 shows to the shown traces.
  void offer_shown(const display::ScanoutSpan& span, const glm::dquat& orientation, const ImageRecord& img) {
    if (listeners_.seen.wants(span)) [[unlikely]]
      listeners_.seen.shown(span, orientation, img);
  }

  FigureWriter figures_;
  const des::Simulator& sim_;
  const tracker::HostFeed& host_;
  ImageBook& images_;
  const display::RasterTiming& timing_;
  SpanListeners listeners_;
  double ipd_m_;
  bool stereo_;
  bool continuation_ = true;
  FrameRecorder* app_frames_ = nullptr;
  std::vector<Pending> pending_;
  int64_t* fields_count_ = nullptr;  // counts.fields once counted
};

}  // namespace latsim::results
