#include "latsim/results/frame_recorder.hpp"

#include "latsim/results/latency_recorder.hpp"
#include "latsim/results/presentmon_log.hpp"

namespace latsim::results {

FrameRecorder::FrameRecorder() = default;
FrameRecorder::~FrameRecorder() = default;
FrameRecorder::FrameRecorder(FrameRecorder&&) noexcept = default;
FrameRecorder& FrameRecorder::operator=(FrameRecorder&&) noexcept = default;

void FrameRecorder::rendered(const FrameTimes& frame) {
  ++rendered_;
  if (log_) log_->completed(frame, *files_);
}

void FrameRecorder::shown(int64_t frame, des::Time first_photon) {
  if (log_) log_->shown(frame, first_photon, *files_);
}

void FrameRecorder::flipped(int64_t frame, des::Time t) {
  if (log_) log_->flipped(frame, t);
}

void FrameRecorder::log_presentmon(RunFiles& files, std::string application) {
  files_ = &files;
  log_ = std::make_unique<PresentMonLog>(std::move(application), presents_);
}

void FrameRecorder::finish(LatencyRecorder& figures, des::Time duration) const {
  if (!declared_) return;
  figures.set("frames_rendered", rendered_);
  if (figures_.rate) figures.set("application_frame_rate_hz", static_cast<double>(rendered_) / duration.to_seconds());
  if (figures_.missed) figures.set("frames_missed", missed_);
}

void FrameRecorder::finish_log(RunFiles& files) {
  if (log_) log_->finish(files);
}

}  // namespace latsim::results
