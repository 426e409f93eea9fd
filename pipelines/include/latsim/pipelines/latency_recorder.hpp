// Turns what the display lights into latency and registration-error samples.
#pragma once

#include <deque>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "latsim/des/simulator.hpp"
#include "latsim/des/stats.hpp"
#include "latsim/display/display.hpp"
#include "latsim/pipelines/figures.hpp"
#include "latsim/pipelines/pipeline.hpp"

namespace latsim::pipelines {

/// Where a probe point is drawn versus where it belongs, per lit field.
struct ProbeSet {
  std::vector<glm::dvec3> points_m;  ///< world points
  double hfov_deg = 90.0;            ///< display field of view (for pixels and visibility)
};

/// Receives every scanout span, looks up the image shown, and records named
/// distributions: motion_to_photon_ms, display_ms, render_latency_ms, image
/// ages, and registration error at probe points. Pipelines add their own
/// named samples through add(), counts through count(), other figures through
/// set() and doubtful input through warn(); figures() is the run's figures.
class LatencyRecorder : public display::ScanoutListener {
 public:
  LatencyRecorder(const des::Simulator& sim, const tracker::MotionSource& motion, const HostFeed& host,
                  const display::RasterTiming& timing, ProbeSet probes, double ipd_m, bool stereo, bool keep_samples);

  /// Registers an image and returns the id to present to the display.
  int64_t register_image(const ImageRecord& record);
  const ImageRecord* image(int64_t id) const;

  /// Adds one sample to the named distribution (created on first use).
  void add(const std::string& name, double value);
  /// The named distribution, created on first use; the reference stays valid
  /// for the recorder's lifetime (hot paths keep it instead of the name).
  des::Distribution& distribution_ref(const std::string& name);
  /// Adds to a named counter.
  void count(const std::string& name, int64_t n = 1);
  const des::Distribution* distribution(const std::string& name) const;
  int64_t counter(const std::string& name) const;
  const std::map<std::string, des::Distribution>& distributions() const { return dists_; }
  const std::map<std::string, int64_t>& counters() const { return counters_; }

  /// A named figure ("frames_rendered", "utilisation.gp", "memories.0.renders").
  void set(const std::string& name, FigureValue value) { table_.set(name, std::move(value)); }
  /// An empty list or object at `name` unless something is set there.
  void list(const std::string& name) { table_.list(name); }
  void object(const std::string& name) { table_.object(name); }
  /// A distribution a model kept itself, reported under `name` like the recorder's own.
  void publish(const std::string& name, const des::Distribution& d) { table_.publish(name, d); }
  /// Legal but doubtful: reported on stderr and in summary.json's "warnings".
  void warn(std::string text) { table_.warn(std::move(text)); }
  const std::vector<std::string>& warnings() const { return table_.warnings(); }
  /// Every figure in the one serialisation of figures.json.
  nlohmann::json figures() const { return table_.to_json(dists_, counters_); }

  void on_field_start(int eye, int64_t field, des::Time retrace) override;
  void on_scanout(const display::ScanoutSpan& span) override;

  /// The display's persistence, so that a probe is judged at the middle of
  /// its pixel's lit interval (nullptr: at its scanout instant).
  void set_persistence(const display::Persistence* persistence) { persistence_ = persistence; }

  /// One row per displayed image: every stage timestamp (the ledger).
  void enable_ledger(bool on) { ledger_on_ = on; }
  const std::vector<nlohmann::json>& ledger() const { return ledger_; }
  /// Raw (time, name, value) samples for samples.csv, when enabled.
  void enable_sample_log(bool on) { sample_log_on_ = on; }
  struct LoggedSample { double t_ms; std::string name; double value; };
  const std::vector<LoggedSample>& sample_log() const { return sample_log_; }

 private:
  struct ProbeHit { int line; double x_px; size_t probe; bool operator<(const ProbeHit& o) const { return line < o.line; } };
  struct ProbeCache { int64_t image_id = -2; int64_t field = -1; int64_t sample_index = -1; std::vector<ProbeHit> hits; };
  void record_probes(const display::ScanoutSpan& span, const tracker::Pose& drawn, int64_t sample_index,
                     int64_t image_id);
  void first_shown(const ImageRecord& img, const display::ScanoutSpan& span);
  void prune(int64_t below_id);

  const des::Simulator& sim_;
  const tracker::MotionSource& motion_;
  const HostFeed& host_;
  const display::RasterTiming& timing_;
  ProbeSet probes_;
  double ipd_m_;
  bool stereo_;
  bool keep_samples_;
  const display::Persistence* persistence_ = nullptr;
  struct Held { ImageRecord record; bool shown = false; };
  std::map<int64_t, Held> images_;
  ProbeCache probe_cache_[2];
  double rad_per_px_ = 0.0;
  int64_t scan_field_ = INT64_MIN;  // field whose scanout start is cached
  des::Time scan_start_;
  double tan_half_h_ = 1.0, tan_half_v_ = 1.0;
  int64_t next_id_ = 0;
  std::map<std::string, des::Distribution> dists_;
  des::Distribution* mtp_ = nullptr;
  des::Distribution* display_ms_ = nullptr;
  des::Distribution* rotation_ = nullptr;
  des::Distribution* translation_ = nullptr;
  des::Distribution* reg_arcmin_ = nullptr;
  des::Distribution* reg_px_ = nullptr;
  void add_to(des::Distribution* d, const char* name, double value);
  std::map<std::string, int64_t> counters_;
  bool ledger_on_ = false;
  std::vector<nlohmann::json> ledger_;
  bool sample_log_on_ = false;
  std::vector<LoggedSample> sample_log_;
  FigureTable table_;
};

}  // namespace latsim::pipelines
