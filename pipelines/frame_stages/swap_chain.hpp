// Shows the application's frames when no compositor stands in between.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <vector>

#include "frame_stages/stage_flow.hpp"
#include "latsim/des/resource.hpp"
#include "latsim/pipelines/pipeline.hpp"

namespace latsim::pipelines::frame_stages {

/// A swap chain of a fixed number of images: with vsync, completed frames
/// queue in frame order and the oldest is swapped in at each retrace (each
/// frame shown at least once); without, a completed frame replaces the
/// front buffer at once (tearing). An image's buffer is returned when a newer
/// frame replaces it on screen.
class SwapChain {
 public:
  SwapChain(RunContext& ctx, des::Resource& images, bool vsync);

  /// The application's frame is complete: register its images, queue or show them.
  void on_frame_complete(const JobRecord& frame);
  /// At a retrace, before scanout: swap the oldest queued frame in.
  void on_retrace(int64_t field);

  int64_t frames_shown() const { return frames_shown_; }
  /// Refreshes at which no new frame was ready (the last one was shown again).

 private:
  struct Done {
    int64_t frame = -1;
    std::vector<int64_t> ids;  ///< per eye
    des::Time completed;
  };
  void show(const Done& d);

  RunContext& ctx_;
  des::Resource& images_;
  bool vsync_;
  std::map<int64_t, Done> early_;  ///< completed ahead of an older frame (alternate frame rendering)
  int64_t next_frame_ = 0;
  std::deque<Done> queue_;
  bool on_screen_ = false;
  int64_t frames_shown_ = 0;
};

}  // namespace latsim::pipelines::frame_stages
