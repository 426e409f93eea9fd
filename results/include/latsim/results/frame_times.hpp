// What is known of one application frame once its work is complete: when its
// CPU and GPU work ran and how long each worked, and when it was presented.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "latsim/des/time.hpp"

namespace latsim::results {

/// The times of one application frame, as its pipeline reports them. CPU work
/// is what runs before the present; GPU work draws the image (docs/figures.md,
/// "presentmon.csv", says which stages are which in each pipeline).
struct FrameTimes {
  int64_t frame = -1;
  bool has_cpu = false;  ///< the pipeline models CPU work before the present
  des::Time cpu_start;   ///< its first CPU stage begins
  des::Time cpu_busy;    ///< the CPU's work on it: its CPU stages' durations as drawn
  des::Time present;     ///< handed to presentation: its last CPU stage ends
  des::Time gpu_start;   ///< its first GPU stage begins
  des::Time gpu_end;     ///< its last GPU stage ends: the image is complete
  des::Time gpu_busy;    ///< the GPU's work on it: its GPU stages' durations as drawn
  /// Its present call's return minus its start, where the pipeline models a
  /// call that can block (present_replay); none where the present takes no time.
  std::optional<des::Time> in_present;
};

/// How a pipeline hands frames to the display.
struct PresentFacts {
  int sync_interval = 1;        ///< refreshes a frame waits for (1: vsync; 0: shown at once)
  bool allows_tearing = false;  ///< a frame may replace another in the middle of a scan
  bool shown = true;            ///< false: no frame is ever shown (a compositor draws its own images)
  std::string present_mode;     ///< PresentMon's PresentMode text, where the pipeline models one (else NA)
};

}  // namespace latsim::results
