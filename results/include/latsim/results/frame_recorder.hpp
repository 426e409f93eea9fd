// The application's frames, as a pipeline emits them: each frame whose work
// is complete, and each that missed the refresh it was paced for. The
// recorder owns the figures (frames_rendered, frames_missed,
// application_frame_rate_hz), so that every pipeline that counts frames
// reports them under one name with one meaning (docs/figures.md), and, when
// the run keeps files, the per-frame log presentmon.csv (PresentMonLog).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "latsim/des/time.hpp"
#include "latsim/results/frame_times.hpp"

namespace latsim::results {

class LatencyRecorder;
class PresentMonLog;
class RunFiles;

class FrameRecorder {
 public:
  /// Which figures a pipeline's frames give: none until it declares them.
  struct Figures {
    bool missed = false;  ///< frames_missed: the pipeline paces frames to refreshes
    bool rate = false;    ///< application_frame_rate_hz: frames rendered per simulated second
  };

  FrameRecorder();
  ~FrameRecorder();
  FrameRecorder(FrameRecorder&&) noexcept;
  FrameRecorder& operator=(FrameRecorder&&) noexcept;

  /// Called by a pipeline that renders frames, before its first frame;
  /// `presents` says how it hands them to the display (presentmon.csv).
  void declare(Figures figures, PresentFacts presents = {}) {
    declared_ = true;
    figures_ = figures;
    presents_ = std::move(presents);
  }
  /// One frame's work is complete.
  void rendered() { ++rendered_; }
  /// The same, with its times (a row of presentmon.csv when it is written).
  void rendered(const FrameTimes& frame);
  /// The first photon of an image showing application frame `frame`.
  void shown(int64_t frame, des::Time first_photon);
  /// Application frame `frame` began to be scanned out at `t`: the retrace
  /// it was swapped in at, or the instant it replaced the front buffer
  /// (PresentMon's display time; pipelines that know it say it).
  void flipped(int64_t frame, des::Time t);
  /// One frame missed the refresh it was due for.
  void missed() { ++missed_; }

  int64_t frames_rendered() const { return rendered_; }
  int64_t frames_missed() const { return missed_; }

  /// From now on log every frame given with its times to presentmon.csv of
  /// `files`, naming the application `application` (written when the first
  /// row is final; nothing when no frame is).
  void log_presentmon(RunFiles& files, std::string application);
  /// Sets the declared figures in `figures` for a run of `duration`.
  void finish(LatencyRecorder& figures, des::Time duration) const;
  /// Completes presentmon.csv (rows still final-less are left out) and
  /// commits it with the run's other files.
  void finish_log(RunFiles& files);

 private:
  bool declared_ = false;
  Figures figures_;
  PresentFacts presents_;
  int64_t rendered_ = 0;
  int64_t missed_ = 0;
  std::unique_ptr<PresentMonLog> log_;  // only when the run keeps presentmon.csv
  RunFiles* files_ = nullptr;           // set with log_
};

}  // namespace latsim::results
