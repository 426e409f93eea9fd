// The application's frames, as a pipeline emits them: each frame whose work
// is complete, and each that missed the refresh it was paced for. The
// recorder owns the figures (frames_rendered, frames_missed,
// application_frame_rate_hz), so that every pipeline that counts frames
// reports them under one name with one meaning (docs/figures.md).
#pragma once

#include <cstdint>

#include "latsim/des/time.hpp"

namespace latsim::results {

class LatencyRecorder;

class FrameRecorder {
 public:
  /// Which figures a pipeline's frames give: none until it declares them.
  struct Figures {
    bool missed = false;  ///< frames_missed: the pipeline paces frames to refreshes
    bool rate = false;    ///< application_frame_rate_hz: frames rendered per simulated second
  };

  /// Called by a pipeline that renders frames, before its first frame.
  void declare(Figures figures) {
    declared_ = true;
    figures_ = figures;
  }
  /// One frame's work is complete.
  void rendered() { ++rendered_; }
  /// One frame missed the refresh it was due for.
  void missed() { ++missed_; }

  int64_t frames_rendered() const { return rendered_; }
  int64_t frames_missed() const { return missed_; }

  /// Sets the declared figures in `figures` for a run of `duration`.
  void finish(LatencyRecorder& figures, des::Time duration) const;

 private:
  bool declared_ = false;
  Figures figures_;
  int64_t rendered_ = 0;
  int64_t missed_ = 0;
};

}  // namespace latsim::results
