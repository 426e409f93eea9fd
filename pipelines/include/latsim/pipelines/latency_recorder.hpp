// Turns what the display lights into latency and registration-error samples.
#pragma once

#include <deque>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "latsim/des/stats.hpp"
#include "latsim/display/display.hpp"
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
/// named samples through add().
class LatencyRecorder : public display::ScanoutListener {
 public:
  LatencyRecorder(const tracker::MotionSource& motion, const HostFeed& host, const display::RasterTiming& timing,
                  ProbeSet probes, double ipd_m, bool stereo, bool keep_samples);

  /// Registers an image and returns the id to present to the display.
  int64_t register_image(const ImageRecord& record);
  const ImageRecord* image(int64_t id) const;

  /// Adds one sample to the named distribution (created on first use).
  void add(const std::string& name, double value);
  /// Adds to a named counter.
  void count(const std::string& name, int64_t n = 1);
  const des::Distribution* distribution(const std::string& name) const;
  int64_t counter(const std::string& name) const;
  const std::map<std::string, des::Distribution>& distributions() const { return dists_; }
  const std::map<std::string, int64_t>& counters() const { return counters_; }

  void on_field_start(int eye, int64_t field, des::Time retrace) override;
  void on_scanout(const display::ScanoutSpan& span) override;

  /// One row per displayed image: every stage timestamp (the ledger).
  void enable_ledger(bool on) { ledger_on_ = on; }
  const std::vector<nlohmann::json>& ledger() const { return ledger_; }
  /// Raw (time, name, value) samples for samples.csv, when enabled.
  void enable_sample_log(bool on) { sample_log_on_ = on; }
  struct LoggedSample { double t_ms; std::string name; double value; };
  const std::vector<LoggedSample>& sample_log() const { return sample_log_; }

 private:
  void record_probes(const display::ScanoutSpan& span, const ImageRecord& img, const tracker::Pose& drawn);
  void first_shown(int64_t id, const ImageRecord& img, const display::ScanoutSpan& span);

  const tracker::MotionSource& motion_;
  const HostFeed& host_;
  const display::RasterTiming& timing_;
  ProbeSet probes_;
  double ipd_m_;
  bool stereo_;
  bool keep_samples_;
  std::unordered_map<int64_t, ImageRecord> images_;
  std::unordered_map<int64_t, bool> shown_;
  int64_t next_id_ = 0;
  std::map<std::string, des::Distribution> dists_;
  std::map<std::string, int64_t> counters_;
  bool ledger_on_ = false;
  std::vector<nlohmann::json> ledger_;
  bool sample_log_on_ = false;
  std::vector<LoggedSample> sample_log_;
  des::Time current_photon_;
};

}  // namespace latsim::pipelines
