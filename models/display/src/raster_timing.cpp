#include "latsim/display/raster_timing.hpp"

#include <stdexcept>

namespace latsim::display {

RasterTiming::RasterTiming(RasterParams params, des::Time t0) : p_(params), schedule_(t0, params.field_period) {
  if (p_.width_px <= 0 || p_.height_px <= 0) throw std::invalid_argument("display size must be positive");
  if (p_.interlaced && p_.height_px % 2 != 0) throw std::invalid_argument("an interlaced display needs an even line count");
  if (p_.vblank_lines < 0 || p_.hblank_px < 0) throw std::invalid_argument("blanking must not be negative");
}

des::Time RasterTiming::field_start(int64_t field) const { return schedule_.at(field); }

des::Time RasterTiming::offset(int64_t slot_times_px) const {
  // offset = slot_px / (total_lines * total_px) of a field period, floored to a
  // tick in 128-bit arithmetic: exact, and identical for every field.
  const __int128 per_field_px = static_cast<__int128>(total_lines_per_field()) * (p_.width_px + p_.hblank_px);
  const __int128 num = static_cast<__int128>(slot_times_px) * p_.field_period.num * des::Time::kTicksPerSecond;
  const __int128 den = per_field_px * p_.field_period.den;
  return des::Time::ps(static_cast<int64_t>(num / den));
}

des::Time RasterTiming::line_time(int64_t field, int j) const {
  const int64_t px_per_line = p_.width_px + p_.hblank_px;
  return field_start(field) + offset(static_cast<int64_t>(p_.vblank_lines + j) * px_per_line);
}

des::Time RasterTiming::pixel_time(int64_t field, int j, int x) const {
  const int64_t px_per_line = p_.width_px + p_.hblank_px;
  return field_start(field) + offset(static_cast<int64_t>(p_.vblank_lines + j) * px_per_line + x);
}

int RasterTiming::parity(int64_t field) const {
  if (!p_.interlaced) return 0;
  const int64_t m = ((field % 2) + 2) % 2;
  return static_cast<int>((m + p_.first_field_parity) % 2);
}

int RasterTiming::row_of(int64_t field, int j) const { return p_.interlaced ? 2 * j + parity(field) : j; }

int RasterTiming::line_of_row(int64_t field, int row) const {
  if (row < 0 || row >= p_.height_px) return -1;
  if (!p_.interlaced) return row;
  return (row % 2 == parity(field)) ? row / 2 : -1;
}

}  // namespace latsim::display
