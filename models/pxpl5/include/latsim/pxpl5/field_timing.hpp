// Retrace and beam times the Pixel-Planes 5 pipelines schedule against.
#pragma once

#include <cstdint>

#include "latsim/des/time.hpp"

namespace latsim::pxpl5 {

/// The display's vertical retraces and the line at which the beam is, kept
/// here so the pxpl5 model needs nothing above the kernel; the pipeline
/// adapters fill it from the display's raster timing.
class FieldTiming {
 public:
  FieldTiming() = default;
  /// Retraces at t0 + k * period; each field has vblank_lines blank lines
  /// then active_lines lit lines, all of equal length; interlaced fields
  /// alternate the rows they light.
  FieldTiming(des::Time t0, des::RationalSeconds period, int vblank_lines, int active_lines, bool interlaced);

  des::Time retrace(int64_t field) const { return schedule_.at(field); }
  /// First field whose retrace is strictly after t (a swap requested at t happens there).
  int64_t field_after(des::Time t) const;
  /// First field whose retrace is at or after t.
  int64_t field_at_or_after(des::Time t) const { return schedule_.index_at_or_after(t); }
  /// When the beam starts lighting active line j of the field.
  des::Time line_time(int64_t field, int line) const;
  des::Time period() const { return schedule_.nominal_period(); }
  double period_ms() const { return schedule_.period().to_seconds() * 1e3; }
  int active_lines() const { return active_lines_; }
  bool interlaced() const { return interlaced_; }

 private:
  des::PeriodicSchedule schedule_;
  int vblank_lines_ = 22;
  int active_lines_ = 240;
  bool interlaced_ = true;
};

}  // namespace latsim::pxpl5
