// What a warped image still gets wrong: the orientation and position parts
// of the difference between the pose it shows and the true pose when lit.
#pragma once

#include <array>
#include <cstdint>

#include "frame_stages/compositor.hpp"
#include "latsim/display/display.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "latsim/tracker/motion_source.hpp"

namespace latsim::pipelines::frame_stages {

/// For every lit span of a compositor's image: the angle between the
/// orientation it shows and the true one at the photon time
/// (`residual_orientation_error_deg`) and the distance between the eye
/// position it shows and the true one (`residual_position_error_mm`); also
/// their means by how many refreshes the image's source had already been
/// shown in (a rotation-only warp of an ever older image leaves a growing
/// position error).
class ResidualErrors final : public display::ScanoutListener {
 public:
  static constexpr int kBuckets = 8;  ///< rewarps 0 .. 6, and 7 or more
  /// Exact sums: the means do not depend on how the display groups samples into spans.
  struct Bucket {
    stats::RunningStats orientation_deg;
    stats::RunningStats position_mm;
    int64_t samples() const { return static_cast<int64_t>(orientation_deg.count()); }
  };

  ResidualErrors(const Compositor& compositor, results::LatencyRecorder& recorder, const tracker::MotionSource& motion,
                 double ipd_m, bool stereo);
  void on_scanout(const display::ScanoutSpan& span) override;
  const std::array<Bucket, kBuckets>& by_rewarps() const { return buckets_; }

 private:
  const Compositor& compositor_;
  results::LatencyRecorder& recorder_;
  const tracker::MotionSource& motion_;
  double ipd_m_;
  bool stereo_;
  stats::Distribution* orientation_ = nullptr;
  stats::Distribution* position_ = nullptr;
  std::array<Bucket, kBuckets> buckets_{};
};

}  // namespace latsim::pipelines::frame_stages
