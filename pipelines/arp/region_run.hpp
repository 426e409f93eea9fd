// One configuration of region priority rendering (segmentation and warping as
// chosen) driven along the run's walk, with what it measured on screen.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "latsim/arp/region_priority_system.hpp"
#include "latsim/arp/seam_meter.hpp"
#include "latsim/des/stats.hpp"

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
  const des::Distribution& tear_gap_px() const { return tear_gap_px_; }
  const des::Distribution& stretch_px() const { return stretch_px_; }

  /// Figures under `prefix` ("" or "variants.0."); says on the recorder's
  /// warnings when the renderers could not keep up.
  void report(results::LatencyRecorder& r, const std::string& prefix, des::Time duration) const;

 private:
  arp::RegionPrioritySystem system_;
  arp::SeamMeter meter_;
  std::vector<std::vector<arp::WarpedPoint>> warped_points_;  // per memory, of its shown image
  std::vector<double> scratch_;
  arp::DisplayMemories::PresentFn present_fn_;
  des::Distribution tear_gap_px_{0.005, false};
  des::Distribution stretch_px_{0.005, false};
};

}  // namespace latsim::pipelines
