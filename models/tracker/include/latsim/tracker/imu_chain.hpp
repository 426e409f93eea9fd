// A headset's tracking chain as its runtime sees it: gyroscope readings
// carried in reports (some lost on the way), an external reference, and
// the runtime's fusion of the two into the pose it predicts from.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "latsim/des/random.hpp"
#include "latsim/des/time.hpp"
#include "latsim/tracker/complementary_filter.hpp"
#include "latsim/tracker/imu.hpp"
#include "latsim/tracker/motion_source.hpp"
#include "latsim/tracker/optical_reference.hpp"

namespace latsim::tracker {

struct TrackerSample;

/// Settings of an IMU tracking chain (/tracker/imu and what goes with it).
struct ImuChainParams {
  ImuParams gyro;
  /// Each report carries the newest this many readings.
  int samples_per_report = 1;
  /// A report is sent every this many readings.
  int report_every = 1;
  /// Chance that a report never reaches the host (independent per report).
  double report_loss_probability = 0.0;
  /// The absolute reference that corrects the gyro (none: the gyro alone).
  std::optional<ReferenceParams> reference;
  FusionParams fusion;
};

/// The readings one report carries, oldest first.
struct ImuReport {
  std::vector<ImuReading> readings;
};

/// The runtime's fusion, fed every report as it becomes visible to the host:
/// it integrates the readings it has not seen, then applies the reference
/// fixes the runtime has by then (measured no later than the newest
/// reading), and returns the report with the fused pose, angular velocity
/// and velocity in place of the raw measurement. The filter starts at the
/// true pose of the first report's first reading (a headset tracked from the start).
class RuntimeFusion {
 public:
  /// `reference_stream` draws the fixes' noise; motion must outlive this.
  RuntimeFusion(const ImuChainParams& params, const MotionSource& motion, des::RandomStream reference_stream);
  TrackerSample fuse(const TrackerSample& report, des::Time visible);
  const ComplementaryFilter& filter() const { return filter_; }

 private:
  const MotionSource& motion_;
  ComplementaryFilter filter_;
  std::optional<OpticalReference> reference_;
  std::optional<ReferenceFix> pending_;  ///< the next fix, not yet applied
};

}  // namespace latsim::tracker
