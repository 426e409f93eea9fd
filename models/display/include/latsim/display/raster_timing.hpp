// Raster timing of a scanned display: when each field starts and when each
// line and pixel of it is lit, computed exactly from the field index.
#pragma once

#include <cstdint>

#include "latsim/des/time.hpp"

namespace latsim::display {

/// Geometry and timing of one raster display.
struct RasterParams {
  des::RationalSeconds field_period{1, 60};  ///< retrace to retrace (exact)
  bool interlaced = false;                   ///< odd/even fields (NTSC) or progressive
  int width_px = 640;                        ///< active pixels per line
  int height_px = 480;                       ///< active lines per frame (both fields together)
  int vblank_lines = 22;                     ///< blank lines at the start of each field
  int hblank_px = 160;                       ///< blank pixel times per line
  int first_field_parity = 0;                ///< interlaced: parity of field 0's rows (0 = rows 0,2,4…)
};

/// Exact photon times of a raster: field k starts (vertical retrace) at
/// t0 + k·period; its j-th active line is lit (vblank + j) line periods later.
class RasterTiming {
 public:
  RasterTiming() = default;
  RasterTiming(RasterParams params, des::Time t0 = des::Time::zero());

  const RasterParams& params() const { return p_; }
  int fields_per_frame() const { return p_.interlaced ? 2 : 1; }
  /// Active lines in every field.
  int lines_per_field() const { return p_.interlaced ? p_.height_px / 2 : p_.height_px; }
  /// Total line periods per field, blanking included.
  int total_lines_per_field() const { return lines_per_field() + p_.vblank_lines; }

  /// Vertical retrace (start of the field's blanking interval).
  des::Time field_start(int64_t field) const;
  /// Photon time of the field's first active line.
  des::Time scanout_start(int64_t field) const { return line_time(field, 0); }
  /// Photon time of the field's j-th active line (j in [0, lines_per_field)).
  des::Time line_time(int64_t field, int j) const;
  /// Photon time of pixel x on the field's j-th active line.
  des::Time pixel_time(int64_t field, int j, int x) const;
  /// Screen row (0 = top) of the field's j-th active line.
  int row_of(int64_t field, int j) const;
  /// Which of the field's lines shows screen row `row`, or -1 if the row is not in this field.
  int line_of_row(int64_t field, int row) const;
  /// Parity (0/1) of the rows field k shows; always 0 when progressive.
  int parity(int64_t field) const;

  /// The field whose retrace is the first at or after t.
  int64_t field_at_or_after(des::Time t) const { return schedule_.index_at_or_after(t); }
  /// The field whose retrace is the last at or before t.
  int64_t field_at_or_before(des::Time t) const { return schedule_.index_at_or_before(t); }
  double field_period_s() const { return p_.field_period.to_seconds(); }
  double field_period_ms() const { return p_.field_period.to_seconds() * 1e3; }

 private:
  // Offset from the field start of line-slot `slot` plus a fraction of a line,
  // as exact integer arithmetic on the rational field period.
  des::Time offset(int64_t slot_times_px) const;

  RasterParams p_;
  des::PeriodicSchedule schedule_;
};

}  // namespace latsim::display
