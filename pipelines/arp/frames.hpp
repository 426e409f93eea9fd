// What the address recalculation pipelines draw when they write frames of
// their display memories, and when.
#pragma once

#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "latsim/pipelines/pipeline.hpp"

namespace latsim::pipelines {

/// Cube faces, background, capture times and threads of display-memory frames.
struct FrameOptions {
  int face_px = 256;
  glm::vec3 background{1.0f};
  std::vector<double> times_s;
  int threads = 1;
};

/// Declares face_px, background, frame_times_s and frame_threads.
void bind(scenario::Section& s, FrameOptions& p);

/// Calls write() at each of the frame times within the run (after the
/// events of the same instant).
void schedule_frames(RunContext& ctx, const FrameOptions& p, std::function<void()> write);

}  // namespace latsim::pipelines
