// One configuration of region priority rendering (segmentation and warping as
// chosen) driven along the run's walk, with what it measured on screen.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "latsim/arp/region_priority_system.hpp"
#include "latsim/arp/seam_meter.hpp"
#include "latsim/stats/stats.hpp"

namespace latsim::results {
class LatencyRecorder;
}

namespace latsim::pipelines {

/// A RegionPrioritySystem plus its tear and stretch measurements.
class RegionRun {
 public:
  RegionRun(des::Simulator& sim, des::KindId render_kind, const arp::SegmentedScene& scene,
            const renderer::RegionGrid& grid, arp::RegionSystemParams params, const renderer::RayCaster* occluder);

  bool segmented() const { return system_.model().scene().segmented; }
  bool warping() const { return system_.params().model.warping; }
  /// "segmented, not warped" and the like.
  std::string label() const;
  arp::RegionPrioritySystem& system() { return system_; }
  const arp::RegionPrioritySystem& system() const { return system_; }
  /// Called with every batch of images presented together (after the run's own bookkeeping).
  void on_present(arp::DisplayMemories::PresentFn fn) { present_fn_ = std::move(fn); }

  /// Measures what the memories show now (at a retrace), the head at
  /// `head` and the user at eye_m: tear gaps and, with warping, stretch.
  void measure(const glm::dquat& head, const glm::dvec3& eye_m, const arp::ScreenProjection& screen);
  const stats::Distribution& tear_gap_px() const { return tear_gap_px_; }
  const stats::Distribution& stretch_px() const { return stretch_px_; }

  /// Figures under `prefix` ("" or "variants.0."); says on the recorder's
  /// warnings when the renderers could not keep up.
  void report(results::LatencyRecorder& r, const std::string& prefix, des::Time duration) const;

  /// The render counts now, opening (then closing) the window that
  /// report_window() describes.
  void mark_window();
  /// Both marks are in.
  bool has_window() const { return window_marks_.size() == 2; }
  /// What memory m's renders that finished between the two marks drew, per
  /// render, and their rate over the window's `length`.
  struct WindowRow {
    int64_t renders = 0;
    double rate_hz = 0.0;
    double segments = 0.0;  ///< object segments
    double drawn = 0.0;     ///< segments or whole objects, each counting once
    double pixels = 0.0;
  };
  WindowRow window_row(int memory, des::Time length) const;
  /// Per memory, what finished between the two marks, under `prefix` + "window."
  void report_window(results::LatencyRecorder& r, const std::string& prefix, des::Time length) const;

 private:
  arp::RegionPrioritySystem system_;
  arp::SeamMeter meter_;
  std::vector<std::vector<arp::WarpedPoint>> warped_points_;  // per memory, of its shown image
  std::vector<double> scratch_;
  arp::DisplayMemories::PresentFn present_fn_;
  stats::Distribution tear_gap_px_{0.005, false};
  stats::Distribution stretch_px_{0.005, false};
  std::vector<std::vector<arp::MemoryRenderCounts>> window_marks_;  // counts at the window's start and end
};

}  // namespace latsim::pipelines
