// Everything one run records, wired together: the figure book, the
// listeners of each figure family, the ledger and the sample log.
#pragma once

#include <optional>

#include "latsim/des/simulator.hpp"
#include "latsim/display/raster_timing.hpp"
#include "latsim/results/figure_book.hpp"
#include "latsim/results/figure_writer.hpp"
#include "latsim/results/image_book.hpp"
#include "latsim/results/image_figures.hpp"
#include "latsim/results/ledger.hpp"
#include "latsim/results/link_figures.hpp"
#include "latsim/results/phase_split.hpp"
#include "latsim/results/prediction_errors.hpp"
#include "latsim/results/registration_errors.hpp"
#include "latsim/results/run_signals.hpp"
#include "latsim/results/seen_figures.hpp"
#include "latsim/results/shown_spans.hpp"
#include "latsim/results/span_latencies.hpp"
#include "latsim/tracker/host_feed.hpp"
#include "latsim/tracker/motion_phase.hpp"
#include "latsim/tracker/motion_source.hpp"

namespace latsim::results {

/// The recorders of one run and the book they write into. The display hands
/// its spans to scanout(), the pipeline emits through signals() and writes
/// its own figures through pipeline_figures(), the link's records go to
/// link(); finish() completes what needs the whole run. Each listener is
/// reached for its own options (seen().film(...), prediction().enable(...)).
class RunRecording {
 public:
  RunRecording(const des::Simulator& sim, const tracker::MotionSource& motion, const tracker::HostFeed& host,
               ImageBook& images, const display::RasterTiming& timing, ProbeSet probes, double ipd_m, bool stereo,
               bool keep_samples);
  RunRecording(const RunRecording&) = delete;
  RunRecording& operator=(const RunRecording&) = delete;

  FigureBook& book() { return book_; }
  const FigureBook& book() const { return book_; }
  /// The pipeline's own figures and warnings (family "pipeline").
  FigureWriter& pipeline_figures() { return pipeline_; }
  RunSignals& signals() { return signals_; }
  /// The display's listener.
  ShownSpans& scanout() { return shown_; }
  SpanLatencies& latencies() { return latencies_; }
  ImageFigures& images() { return images_; }
  RegistrationErrors& registration() { return registration_; }
  PredictionErrors& prediction() { return prediction_; }
  SeenFigures& seen() { return seen_; }
  LinkFigures& link() { return link_; }

  /// Splits registration_error_arcmin and prediction_error_deg by the motion
  /// phase at their photon (or target) time into <name>_still, _onset,
  /// _steady and _stop.
  void split_by_phase(const tracker::MotionPhaseParams& params);
  /// The ledger (frames.csv, fields.csv, tracker.csv), kept when enabled.
  void keep_ledger(bool on);
  const Ledger& ledger() const { return ledger_; }
  /// Raw (time, name, value) samples for samples.csv, when enabled.
  void keep_sample_log(bool on);
  const SampleLog& sample_log() const { return book_.sample_log(); }

  /// Completes the figures that need the whole run (pending spans, frame
  /// rate, missed refreshes, what was seen, the link's load) and warns about
  /// overload.
  void finish(const RunTotals& totals);

 private:
  FigureBook book_;
  const tracker::MotionSource& motion_;
  ImageBook& image_book_;
  Ledger ledger_;
  FigureWriter pipeline_;
  FigureWriter run_;
  std::optional<MotionPhases> phases_;
  SpanLatencies latencies_;
  ImageFigures images_;
  RegistrationErrors registration_;
  PredictionErrors prediction_;
  SeenFigures seen_;
  LinkFigures link_;
  ShownSpans shown_;
  RunSignals signals_;
};

}  // namespace latsim::results
