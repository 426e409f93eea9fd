// Splitting a figure's samples by the motion phase of the true head.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "latsim/des/time.hpp"
#include "latsim/results/figure_writer.hpp"
#include "latsim/stats/stats.hpp"
#include "latsim/tracker/motion_phase.hpp"
#include "latsim/tracker/motion_source.hpp"

namespace latsim::results {

/// The motion phases of the run (/motion_phases), one classifier shared by
/// every figure split by them.
class MotionPhases {
 public:
  MotionPhases(const tracker::MotionSource& motion, const tracker::MotionPhaseParams& params) : classifier_(motion, params) {}
  tracker::MotionPhase at(des::Time t) { return classifier_.phase_at(t); }

 private:
  tracker::MotionPhaseClassifier classifier_;
};

/// One figure split into <name>_still, _onset, _steady and _stop.
class PhaseSplit {
 public:
  explicit PhaseSplit(const char* name) : name_(name) {}
  /// Adds `value` to the part of the phase at `at`, when the run splits by phase.
  void add(MotionPhases* phases, FigureWriter& figures, double value, des::Time at) {
    if (phases == nullptr) return;
    const tracker::MotionPhase phase = phases->at(at);
    const std::string name = std::string(name_) + "_" + std::string(tracker::phase_name(phase));
    figures.add(parts_[static_cast<size_t>(phase)], name.c_str(), value);
  }

 private:
  const char* name_;
  std::array<stats::Distribution*, 4> parts_{};
};

}  // namespace latsim::results
