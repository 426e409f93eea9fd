// Raster timing of a scanned display: when each field starts and when each
// line and pixel of it is lit, computed exactly from the field index.
#pragma once

#include <cstdint>
#include <memory>

#include "latsim/stats/tick_run.hpp"
#include "latsim/des/time.hpp"
#include "latsim/display/clock_noise.hpp"

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
/// t0 + k·period (plus the clock noise's offset D(k) when the display clock
/// jitters or wanders); its j-th active line is lit (vblank + j) line periods
/// later.
///
/// A pixel's offset from its field's start is floor(slot · K / D) ticks, slot
/// counting pixel times from the retrace (blanking included), K / D the pixel
/// time in ticks as a reduced fraction. Runs of evenly spaced pixels or lines
/// are stats::TickRun values, which a stats::TickStepper walks without dividing.
class RasterTiming {
 public:
  RasterTiming() = default;
  RasterTiming(RasterParams params, des::Time t0 = des::Time::zero());

  /// Moves every retrace by `noise`'s offset (nullptr: a steady clock, at no
  /// cost). Lines and pixels keep their offsets from their own field's start.
  void set_clock_noise(std::shared_ptr<const ClockNoise> noise) { noise_ = std::move(noise); }
  const ClockNoise* clock_noise() const { return noise_.get(); }
  /// Blank time from the field's last lit pixel to the nominal next retrace:
  /// how far the clock may shorten a field before fields overlap.
  des::Time end_slack() const;

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
  /// Pixel times from the retrace to the field's j-th line's pixel x.
  int64_t slot(int j, int x) const { return static_cast<int64_t>(p_.vblank_lines + j) * pixels_per_line() + x; }
  /// Pixel times per line, blanking included.
  int64_t pixels_per_line() const { return static_cast<int64_t>(p_.width_px) + p_.hblank_px; }
  /// Photon times of `count` samples from pixel x of the field's j-th line on,
  /// `slot_step` pixel times apart (pixels_per_line() steps line by line).
  stats::TickRun photon_run(int64_t field, int j, int x, int64_t slot_step, uint64_t count) const;


  /// Ticks per pixel time, K / D; the numerator K (what a pixel or line step
  /// is a multiple of).
  stats::i128 ticks_per_slot_num() const { return k_; }
  /// The field whose retrace is the first at or after t.
  int64_t field_at_or_after(des::Time t) const {
    return noise_ ? noisy_index_at_or_after(t) : schedule_.index_at_or_after(t);
  }
  /// The field whose retrace is the last at or before t.
  int64_t field_at_or_before(des::Time t) const {
    return noise_ ? noisy_index_at_or_after(t + des::Time::ps(1)) - 1 : schedule_.index_at_or_before(t);
  }
  double field_period_ms() const { return p_.field_period.to_seconds() * 1e3; }

 private:
  // Offset from the field start of line-slot `slot` plus a fraction of a line,
  // as exact integer arithmetic on the rational field period.
  des::Time offset(int64_t slot_times_px) const;
  // field_at_or_after with clock noise: retraces stay in order, so a search
  // from the steady clock's answer, moved by the noise there.
  int64_t noisy_index_at_or_after(des::Time t) const;

  RasterParams p_;
  des::PeriodicSchedule schedule_;
  stats::i128 k_ = 1;  // ticks per pixel time = k_ / d_, reduced
  stats::i128 d_ = 1;
  std::shared_ptr<const ClockNoise> noise_;
};

}  // namespace latsim::display
