#include "passthrough/camera_timing.hpp"

#include <algorithm>
#include <cmath>

namespace latsim::pipelines::passthrough {

CameraTiming::CameraTiming(const CameraSpec& spec, const display::RasterTiming& display)
    : spec_(spec), display_(&display) {}

CameraTiming::CameraTiming(const CameraSpec& spec, des::PeriodicSchedule clock) : spec_(spec), clock_(clock) {}

des::Time CameraTiming::frame_start(int64_t k) const {
  if (clock_) return clock_->at(k);
  return display_->field_start(k * spec_.refreshes_per_frame) + spec_.sync_offset;
}

int64_t CameraTiming::row_at(double y) const {
  const auto row = static_cast<int64_t>(std::floor(y * static_cast<double>(spec_.height_px)));
  return std::clamp<int64_t>(row, 0, spec_.height_px - 1);
}

des::Time CameraTiming::row_open(int64_t k, int64_t row) const {
  const des::Time start = frame_start(k);
  if (spec_.shutter == CameraSpec::Shutter::global) return start;
  return start + des::Time::ps(spec_.row_readout.ticks() * row);
}

des::Time CameraTiming::exposure_middle(int64_t k, int64_t row) const {
  return row_open(k, row) + des::Time::ps(spec_.exposure.ticks() / 2);
}

des::Time CameraTiming::readout_start(int64_t k) const {
  // Global: the rows are read one after another once the shutter closes;
  // rolling: row 0 closes at the exposure's end and is read in its row time.
  return frame_start(k) + spec_.exposure + spec_.row_readout;
}

des::Time CameraTiming::readout_end(int64_t k) const { return frame_start(k) + spec_.exposure + spec_.readout(); }

}  // namespace latsim::pipelines::passthrough
