// Smear on a persistent display: how far a lit pixel's image slides across
// the retina while the head turns (SPEC section 10).
#pragma once

#include "latsim/stats/stats.hpp"
#include "latsim/display/display.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "latsim/tracker/motion_source.hpp"

namespace latsim::results {

/// Angular speed of the head at t in rad/s: the rotation between the true
/// orientations 0.5 ms either side of t (from t on, before 0.5 ms), over the
/// interval. Exact for a constant rate.
double head_angular_speed_rad_s(const tracker::MotionSource& motion, des::Time t);

/// Adds `smear_arcmin` = head angular speed at the middle of the lit
/// interval x lit duration, for every scanned span of a display with
/// persistence (the eye, fixed on the world, turns against the head while
/// the panel holds the pixel still). Registered only when the display has a
/// persistence model, so an impulse display pays nothing.
class SmearRecorder final : public display::ScanoutListener {
 public:
  SmearRecorder(LatencyRecorder& recorder, const tracker::MotionSource& motion);
  void on_scanout(const display::ScanoutSpan& span) override;

 private:
  stats::Distribution& smear_;
  const tracker::MotionSource& motion_;
  bool still_;
};

}  // namespace latsim::results
