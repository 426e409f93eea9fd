// The external reference a headset's fusion corrects its gyroscope with:
// Lighthouse sweeps or inside-out camera frames, each an absolute pose
// measured at one instant and known to the runtime some time later.
#pragma once

#include <cstdint>

#include "latsim/des/clock.hpp"
#include "latsim/des/random.hpp"
#include "latsim/des/time.hpp"
#include "latsim/tracker/motion_source.hpp"
#include "latsim/tracker/pose.hpp"

namespace latsim::tracker {

/// How often the reference measures the pose, how late the runtime has it and how noisy it is.
struct ReferenceParams {
  des::RationalSeconds period{1, 60};   ///< one complete pose per period
  des::ClockSettings clock;             ///< time of fix 0 (a run draws it when the scenario leaves it out), rate error
  des::Time latency = des::Time::ms(5); ///< from the measurement to the fusion having it
  double orientation_stddev_deg = 0.0;  ///< per axis
  double position_stddev_m = 0.0;       ///< per axis
};

/// One absolute pose measurement.
struct ReferenceFix {
  int64_t index = 0;
  des::Time measured_at;
  des::Time available_at;  ///< measured_at + latency
  Pose pose;               ///< noise included
};

/// Fixes k = 0, 1, ... of a motion at phase + k * period, with normal noise
/// (stream substream "noise"; nothing drawn without noise). Fixes must be
/// asked for in increasing index.
class OpticalReference {
 public:
  OpticalReference(ReferenceParams params, const MotionSource& motion, des::RandomStream stream);
  ReferenceFix fix(int64_t k);
  /// The first fix whose measurement is at or after t.
  int64_t first_index_at_or_after(des::Time t) const { return schedule_.index_at_or_after(t); }
  const ReferenceParams& params() const { return params_; }

 private:
  ReferenceParams params_;
  des::PeriodicSchedule schedule_;
  const MotionSource& motion_;
  des::RandomStream noise_;
};

}  // namespace latsim::tracker
