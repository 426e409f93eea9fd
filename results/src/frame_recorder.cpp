#include "latsim/results/frame_recorder.hpp"

#include "latsim/results/latency_recorder.hpp"

namespace latsim::results {

void FrameRecorder::finish(LatencyRecorder& figures, des::Time duration) const {
  if (!declared_) return;
  figures.set("frames_rendered", rendered_);
  if (figures_.rate) figures.set("application_frame_rate_hz", static_cast<double>(rendered_) / duration.to_seconds());
  if (figures_.missed) figures.set("frames_missed", missed_);
}

}  // namespace latsim::results
