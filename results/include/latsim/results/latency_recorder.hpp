// Turns what the display lights into the figures of docs/figures.md.
#pragma once

#include <array>
#include <optional>
#include <cstdint>
#include <deque>
#include <map>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "latsim/stats/run_feed.hpp"
#include "latsim/des/simulator.hpp"
#include "latsim/stats/stats.hpp"
#include "latsim/display/display.hpp"
#include "latsim/measurement/apparent_latency.hpp"
#include "latsim/measurement/camera_rig.hpp"
#include "latsim/measurement/shown_trace.hpp"
#include "latsim/results/figures.hpp"
#include "latsim/results/image_book.hpp"
#include "latsim/results/image_record.hpp"
#include "latsim/results/ledger.hpp"
#include "latsim/tracker/host_feed.hpp"
#include "latsim/tracker/motion_phase.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::results {

class Timeline;
class FrameRecorder;

/// Where a probe point is drawn versus where it belongs, per lit field.
struct ProbeSet {
  std::vector<glm::dvec3> points_m;  ///< world points
  double hfov_deg = 90.0;            ///< display field of view (for pixels and visibility)
};

/// What the run knows at its end about its shared models.
struct RunTotals {
  des::Time duration;
  int64_t fields = 0;            ///< retraces the display made
  int64_t tracker_samples = 0;   ///< samples measured
  des::Time tracker_period;      ///< actual sampling period (for overload messages)
  /// The link: records offered, dropped, still waiting; its occupancy, buffer and handler time per record.
  int64_t records_dropped = 0;
  int64_t records_waiting = 0;
  des::Time line_occupancy;      ///< zero: a link without a line (direct)
  int64_t buffer_records = 0;
  des::Time handler_time;        ///< interrupt handlers per record (zero: none modelled)
  std::string link_description;  ///< e.g. "40-byte records at 19200 baud"
};

/// The one place where the figures of the glossary (docs/figures.md) are
/// computed, for every pipeline. It receives every scanout span, looks up the
/// image shown and records motion-to-photon, rotation and translation
/// latency, display delay, image age and registration error at probe points;
/// per image, render latency; per record, the link's delays; at the end,
/// frame rate, missed refreshes and the link's load. Pipelines that light
/// pixels without whole images report them through pixel_lit(). Pipeline
/// figures go through add(), count(), set() and publish(), which refuse a
/// glossary name and a name already taken: no figure is ever overwritten.
class LatencyRecorder : public display::ScanoutListener {
 public:
  /// Looks up in `images` the image each span shows.
  LatencyRecorder(const des::Simulator& sim, const tracker::MotionSource& motion, const tracker::HostFeed& host,
                  ImageBook& images, const display::RasterTiming& timing, ProbeSet probes, double ipd_m, bool stereo,
                  bool keep_samples);

  /// Where the host application stage (sample visible to render start) is logged.
  void set_timeline(Timeline* timeline) { timeline_ = timeline; }
  /// Told the first photon of every image of an application frame (presentmon.csv).
  void set_frame_recorder(FrameRecorder* frames) { app_frames_ = frames; }

  /// The images of the run, which pipelines register in and present by id.
  const ImageBook& images() const { return images_; }
  /// The pipeline shows whole images (it has a frame rate, and a run that
  /// shows none is warned about).
  void expects_images() { expects_images_ = true; }
  /// A render began that the pipeline means to show by the first refresh at
  /// or after `due_by`; every refresh from then on that shows no new image
  /// counts as missed until one is shown. A pipeline that never calls this
  /// sets itself no refresh deadline and reports no missed_refreshes.
  void image_due(des::Time due_by);

  /// A pixel lit at `photon` with a colour computed wholly from sample `s`
  /// (frameless rendering): motion-to-photon, rotation, translation and pixel age.
  void pixel_lit(const tracker::TrackerSample& s, des::Time photon);
  /// Age of a sampled pixel of a whole image computed from `s`.
  void pixel_age(const tracker::TrackerSample& s, des::Time photon);
  /// Registration error of world point `point_m`, drawn along head-frame
  /// direction `drawn_head_dir` of eye `eye`, lit at `photon`.
  void registration(int eye, const glm::dvec3& point_m, const glm::dvec3& drawn_head_dir, des::Time photon);
  /// A record given to the link (`line`: a serial line, whose wait is reported).
  void record_carried(const tracker::TrackerSample& s, const tracker::Carriage& c, bool line);

  /// Adds one sample to the named distribution (created on first use).
  void add(const std::string& name, double value);
  /// The named distribution, created on first use; the reference stays valid
  /// for the recorder's lifetime (hot paths keep it instead of the name).
  stats::Distribution& distribution_ref(const std::string& name);
  /// Adds to a named counter.
  void count(const std::string& name, int64_t n = 1);
  const stats::Distribution* distribution(const std::string& name) const;
  int64_t counter(const std::string& name) const;
  const std::map<std::string, stats::Distribution>& distributions() const {
    runs_.close_all();
    return dists_;
  }
  const std::map<std::string, int64_t>& counters() const { return counters_; }

  /// A named figure ("frames_rendered", "utilisation.gp", "memories.0.renders").
  void set(const std::string& name, FigureValue value);
  /// An empty list or object at `name` unless something is set there.
  void list(const std::string& name);
  void object(const std::string& name);
  /// A distribution a model kept itself, reported under `name` like the recorder's own.
  void publish(const std::string& name, const stats::Distribution& d);
  /// The figures a reader of this pipeline means first (in tables, plots and
  /// the run line), in order; a name whose figure the run lacks is left out.
  /// Pipelines that declare none get default_headline().
  void declare_headline(std::vector<std::string> names) { headline_ = std::move(names); }
  /// The declared headline figures that the run has (after finish()).
  std::vector<std::string> headline() const { return headline(figures()); }
  /// The same, from the run's figures() already in hand (they take a while to make).
  std::vector<std::string> headline(const nlohmann::json& figures) const;
  /// The headline of a pipeline that declares none.
  static std::vector<std::string> default_headline();
  /// What a measured cost read and played (summary.json's "captures").
  void add_capture(nlohmann::json entry) { captures_.push_back(std::move(entry)); }
  const nlohmann::json& captures() const { return captures_; }
  /// Legal but doubtful: reported on stderr and in summary.json's "warnings".
  void warn(std::string text) { table_.warn(std::move(text)); }
  const std::vector<std::string>& warnings() const { return table_.warnings(); }

  /// Completes the figures that need the whole run (pending spans, frame
  /// rate, missed refreshes, the link's load) and warns about overload.
  void finish(const RunTotals& totals);
  /// Every figure in the one serialisation of figures.json.
  nlohmann::json figures() const { return table_.to_json(distributions(), counters_); }

  /// Prediction figures: per image shown, prediction_error_deg (predicted
  /// against true head orientation at the instant predicted for),
  /// prediction_error_mm (position) and prediction_horizon_ms.
  void enable_prediction(bool on);
  /// Splits registration_error_arcmin and prediction_error_deg by the
  /// motion phase at their photon (or target) time into <name>_still,
  /// _onset, _steady and _stop.
  void split_by_phase(const tracker::MotionPhaseParams& params);
  /// One prediction: its error against the truth at its target, in degrees
  /// (when `orientation`) and millimetres (when `position`), and its horizon.
  void add_prediction_error(const tracker::PosePrediction& prediction, bool orientation, bool position);

  /// Keeps the orientation shown at the centre of eye 0's display, one
  /// sample per refresh, and at finish() reports apparent_latency_ms (split
  /// by the motion phases of `phases`) and prediction_catch_up_ms.
  void measure_apparent_latency(const measurement::ApparentLatencyParams& params,
                                const tracker::MotionPhaseParams& phases);
  /// Keeps the orientation shown at the rig's display point and at finish()
  /// films it and the true head with a camera whose frames open at `camera`.
  void film(const measurement::CameraRigParams& params, const des::PeriodicSchedule& camera);
  /// A tracked controller moving as `motion` (which must outlive the
  /// recorder): keeps, one sample per refresh at the centre of eye 0's
  /// display (and at the rig's point), the controller orientation a viewer
  /// sees, and at finish() reports controller_latency_ms and, with apparent
  /// latency, controller_apparent_latency_ms; the rig films it when its
  /// object is the controller.
  void track_controller(const tracker::MotionSource& motion);

  void on_field_start(int eye, int64_t field, des::Time retrace) override;
  void on_scanout(const display::ScanoutSpan& span) override;

  /// The display's persistence, so that a probe is judged at the middle of
  /// its pixel's lit interval (nullptr: at its scanout instant).
  void set_persistence(const display::Persistence* persistence) { persistence_ = persistence; }

  /// The ledger (frames.csv, fields.csv, tracker.csv), kept when enabled.
  void enable_ledger(bool on) {
    ledger_.enable(on);
    hot_[0].valid = hot_[1].valid = false;
  }
  const Ledger& ledger() const { return ledger_; }
  /// Raw (time, name, value) samples for samples.csv, when enabled.
  void enable_sample_log(bool on) {
    sample_log_.enable(on);
    hot_[0].valid = hot_[1].valid = false;
  }
  const SampleLog& sample_log() const { return sample_log_; }

 private:
  struct ProbeHit { int line; double x_px; size_t probe; bool operator<(const ProbeHit& o) const { return line < o.line; } };
  struct ProbeCache {
    int64_t image_id = -2;
    int64_t field = -1;
    bool image_pose = false;  ///< projected with the image's own pose (sample_index and orientation unused)
    int64_t sample_index = -1;
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  ///< the drawn orientation the hits were projected with
    std::vector<ProbeHit> hits;                   ///< sorted by line
    std::vector<size_t> first_hit;                ///< per line of the field (and one past): its first hit
    int lookups = 0;                              ///< spans served before first_hit was built
  };
  /// A span whose orientation must come from a sample not simulated yet.
  struct Pending { ImageRecord record; display::ScanoutSpan span; };

  void record_span(const ImageRecord& img, const display::ScanoutSpan& span);
  /// A span whose every sample shows one orientation: `newest` for an address
  /// recalculation image (none: no sample visible yet), else the image's.
  void record_uniform(const ImageRecord& img, const display::ScanoutSpan& span,
                      const std::optional<tracker::PosePrediction>& newest);
  /// Samples [begin, begin + n) of a span: lines at field fidelity, columns
  /// of one line at batched pixel fidelity.
  display::ScanoutSpan samples_of(const display::ScanoutSpan& span, uint64_t begin, uint64_t n) const;
  /// Whether the span's lines light no probe, known without projecting.
  bool no_probe_on(const display::ScanoutSpan& span) const;
  /// record_uniform() with the orientation the image was drawn (or warped) to.
  void record_image_pose(const ImageRecord& img, const display::ScanoutSpan& span);
  /// Registration error of the probes lit by a span, drawn with `orientation`
  /// (from sample `sample_index`, or the image's own when image_pose) and the
  /// image's position.
  void record_probes(const display::ScanoutSpan& span, const glm::dquat& orientation, const glm::dvec3& position_m,
                     int64_t sample_index, int64_t image_id, bool image_pose);
  using PhaseSplit = std::array<stats::Distribution*, 4>;
  void add_split(PhaseSplit& split, const char* name, double value, des::Time at);
  void first_shown(const ImageRecord& img, const display::ScanoutSpan& span);
  void flush_pending();
  void close_field();
  void prune(int64_t below_id);
  /// Glossary figures only through here; pipelines through add().
  void record(stats::Distribution*& d, const char* name, double value);
  /// A duration, kept exactly (a glossary duration is only ever recorded so).
  void record(stats::Distribution*& d, const char* name, des::Time value);
  /// The glossary distribution `name` behind handle d, created on first use.
  stats::Distribution& figure(stats::Distribution*& d, const char* name);
  /// Motion-to-photon, rotation and translation latency and display delay of
  /// every sample of a span (photon - origin), in closed form for a run.
  void record_spans(const display::ScanoutSpan& span, des::Time orientation_measured, des::Time position_measured);
  /// The samples of a span for samples.csv, logged at each sample's write, or
  /// now when that is earlier (a field computed ahead at its retrace), as the
  /// per-sample events would.
  void log_run(const char* name, const display::ScanoutSpan& span, des::Time origin);
  void refuse(const std::string& name, const char* how) const;
  /// Hands the orientation a span of eye 0 shows (and the controller of its
  /// image) to the shown traces whose pixel it lights.
  void offer_shown(const display::ScanoutSpan& span, const glm::dquat& orientation, const ImageRecord& img) {
    if (shown_traces_ != 0 && span.eye == 0) [[unlikely]]
      offer_shown_slow(span, orientation, img);
  }
  void offer_shown_slow(const display::ScanoutSpan& span, const glm::dquat& orientation, const ImageRecord& img);
  /// The figures of measure_apparent_latency(), film() and track_controller().
  void measurement_figures(des::Time duration);
  /// The shown trace at the centre of eye 0's display, kept once for apparent
  /// latency and the controller alike.
  void keep_centre_trace();
  /// Apparent latency of `shown` against `truth`, as figures named `prefix` + apparent_latency_ms ….
  void apparent_figures(const std::string& prefix, std::span<const measurement::ShownSample> shown,
                        const tracker::MotionSource& truth);
  /// The camera rig filming `truth` and the angles `shown` at its display point.
  void rig_figures(std::span<const measurement::ShownSample> shown, const tracker::MotionSource& truth,
                   des::Time duration);
  void link_figures(const RunTotals& totals);

  const des::Simulator& sim_;
  const tracker::MotionSource& motion_;
  const tracker::HostFeed& host_;
  ImageBook& images_;
  const display::RasterTiming& timing_;
  ProbeSet probes_;
  double ipd_m_;
  bool stereo_;
  bool keep_samples_;
  const display::Persistence* persistence_ = nullptr;
  Timeline* timeline_ = nullptr;
  FrameRecorder* app_frames_ = nullptr;
  std::vector<Pending> pending_;
  ProbeCache probe_cache_[2];
  // Per eye: the image and field of the last span recorded with the image's
  // own pose, while the run it was added to is the eye's open run with that
  // span's targets (record_spans() clears it before any other add).
  struct HotSpan {
    int64_t image_id = -1;
    int64_t field = INT64_MIN;
    bool valid = false;
  };
  HotSpan hot_[2];
  double rad_per_px_ = 0.0;
  int64_t scan_field_ = INT64_MIN;  // field whose scanout start is cached
  des::Time scan_start_;
  double tan_half_h_ = 1.0, tan_half_v_ = 1.0;
  std::map<std::string, stats::Distribution> dists_;
  stats::Distribution* mtp_ = nullptr;
  stats::Distribution* display_ms_ = nullptr;
  stats::Distribution* rotation_ = nullptr;
  stats::Distribution* translation_ = nullptr;
  stats::Distribution* image_age_ = nullptr;
  stats::Distribution* pixel_age_ = nullptr;
  stats::Distribution* reg_arcmin_ = nullptr;
  stats::Distribution* reg_px_ = nullptr;
  stats::Distribution* render_latency_ = nullptr;
  stats::Distribution* render_latency_fields_ = nullptr;
  stats::Distribution* tracker_to_render_ = nullptr;
  stats::Distribution* tracker_to_host_ = nullptr;
  stats::Distribution* line_wait_ = nullptr;
  bool predicting_ = false;
  std::optional<tracker::MotionPhaseClassifier> phases_;
  stats::Distribution* prediction_horizon_ = nullptr;
  stats::Distribution* prediction_deg_ = nullptr;
  stats::Distribution* prediction_mm_ = nullptr;
  PhaseSplit reg_split_{};
  PhaseSplit prediction_split_{};
  std::map<std::string, int64_t> counters_;
  nlohmann::json captures_ = nlohmann::json::array();
  int64_t* fields_count_ = nullptr;        // counters_["fields"] once counted
  int64_t* images_shown_count_ = nullptr;  // counters_["images_shown"] once counted
  // The runs of the span figures, gathered across spans; closed whenever the
  // figures are read, so they are always complete (hence mutable).
  mutable stats::RunFeed runs_;
  // Refresh deadlines: due times of renders not yet shown, oldest first, and
  // the field (one eye) being scanned now.
  std::deque<des::Time> due_;
  bool deadlines_ = false;
  bool expects_images_ = false;
  int64_t open_field_ = INT64_MIN;
  des::Time open_retrace_;
  bool new_in_open_field_ = false;
  int64_t missed_ = 0;
  int64_t first_shown_eye0_ = 0;
  int64_t records_offered_ = 0;
  Ledger ledger_;
  SampleLog sample_log_;
  FigureTable table_;
  std::vector<std::string> headline_;
  // Apparent latency and the camera rig (absent unless the scenario asks).
  int shown_traces_ = 0;
  std::optional<measurement::ShownTrace> centre_trace_;
  std::optional<measurement::ApparentLatencyParams> apparent_;
  const tracker::MotionSource* controller_ = nullptr;
  tracker::MotionPhaseParams apparent_phases_;
  std::optional<measurement::ShownTrace> rig_trace_;
  measurement::CameraRigParams rig_;
  des::PeriodicSchedule camera_;
};

}  // namespace latsim::results
