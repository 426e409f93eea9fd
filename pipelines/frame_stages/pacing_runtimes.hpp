// The runtimes' own pacing rules as they document them: SteamVR (running
// start, throttling with interleaved reprojection or motion smoothing) and
// the Oculus runtimes (Phase Sync with Asynchronous Spacewarp).
#pragma once

#include <deque>

#include "latsim/des/time.hpp"

namespace latsim::pipelines::frame_stages {

/// How a runtime drops the application to a fraction of the refresh rate
/// and brings it back: the throttle level rises after `late_threshold` late
/// frames among the last `window`, and falls after `early_frames` frames in
/// a row that would have made the level below (Valve's patent US 10,600,236:
/// "Prediction and throttling adjustments based on application rendering
/// performance"; the numbers are assumptions, docs/pacing.md).
struct ThrottleParams {
  int max_level = 1;        ///< the application runs at 1 / (level + 1) of the refresh rate at most
  int window = 20;
  int late_threshold = 5;
  int early_frames = 30;
};

/// SteamVR's pacing (/pipeline/pacing/steamvr).
struct SteamVrParams {
  /// WaitGetPoses returns this long before a retrace: the running start
  /// (Vlachos, "Advanced VR Rendering", GDC 2015: about 3 ms).
  des::Time running_start = des::Time::ms(3);
  /// What SteamVR does when the application cannot hold the rate.
  enum class Reprojection {
    off,               ///< nothing: late frames are re-projected as they come (asynchronous reprojection)
    interleaved,       ///< throttled to half rate, every other refresh re-projected
    motion_smoothing,  ///< throttled to 1/2, 1/3 or 1/4, the other refreshes synthesised
  };
  Reprojection reprojection = Reprojection::interleaved;
  ThrottleParams throttle;
};

/// The Oculus runtimes' pacing (/pipeline/pacing/oculus): Phase Sync and ASW.
struct OculusParams {
  double percentile = 99.0;               ///< Phase Sync: of the last `window` frame times
  int window = 32;
  des::Time margin = des::Time::ms(1);
  bool asw = true;                        ///< Asynchronous Spacewarp: half rate with synthesised frames
  ThrottleParams throttle;
};

/// The throttle level from frames late and early.
class RuntimeThrottle {
 public:
  explicit RuntimeThrottle(const ThrottleParams& p) : p_(p) {}
  int level() const { return level_; }
  /// One frame measured: late (it missed what its level allows) or early
  /// (it would have made the level below).
  void frame(bool late, bool early);
  /// Times the level went up.
  int64_t raised() const { return raised_; }

 private:
  ThrottleParams p_;
  int level_ = 0;
  std::deque<bool> recent_;
  int early_run_ = 0;
  int64_t raised_ = 0;
};

}  // namespace latsim::pipelines::frame_stages
