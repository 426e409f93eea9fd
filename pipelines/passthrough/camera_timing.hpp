// When the see-through camera exposes and reads out each row of each frame,
// from its frame index: phase-locked to the display's retraces or on a clock
// of its own.
#pragma once

#include <cstdint>
#include <optional>

#include "latsim/des/time.hpp"
#include "latsim/display/raster_timing.hpp"
#include "passthrough/passthrough_spec.hpp"

namespace latsim::pipelines::passthrough {

/// Exact exposure and readout instants of the camera's frames: frame k's
/// first row opens at frame_start(k), a global shutter exposes every row
/// then and reads them one after another once it closes, a rolling shutter
/// opens row j j row-times later and reads it as it closes. Either way the
/// last row is read exposure + height_px row-times after frame_start(k).
class CameraTiming {
 public:
  /// Phase-locked: frame k starts spec.sync_offset after retrace k x refreshes_per_frame of `display`.
  CameraTiming(const CameraSpec& spec, const display::RasterTiming& display);
  /// Free-running: frame k starts at `clock.at(k)`.
  CameraTiming(const CameraSpec& spec, des::PeriodicSchedule clock);

  des::Time frame_start(int64_t k) const;
  /// The camera row (0: top) imaging a point at fraction `y` of the image's height.
  int64_t row_at(double y) const;
  /// When row `row` of frame k opens.
  des::Time row_open(int64_t k, int64_t row) const;
  /// The middle of row `row`'s exposure in frame k (integer picoseconds, rounded down).
  des::Time exposure_middle(int64_t k, int64_t row) const;
  /// When the first row of frame k has been read (the frame's readout starts).
  des::Time readout_start(int64_t k) const;
  /// When the last row of frame k has been read.
  des::Time readout_end(int64_t k) const;
  const CameraSpec& spec() const { return spec_; }

 private:
  CameraSpec spec_;
  const display::RasterTiming* display_ = nullptr;
  std::optional<des::PeriodicSchedule> clock_;
};

}  // namespace latsim::pipelines::passthrough
