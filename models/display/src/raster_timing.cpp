#include "latsim/display/raster_timing.hpp"

#include <stdexcept>

namespace latsim::display {

namespace {

stats::i128 gcd(stats::i128 a, stats::i128 b) {
  while (b != 0) {
    const stats::i128 r = a % b;
    a = b;
    b = r;
  }
  return a;
}

}  // namespace

RasterTiming::RasterTiming(RasterParams params, des::Time t0) : p_(params), schedule_(t0, params.field_period) {
  if (p_.width_px <= 0 || p_.height_px <= 0) throw std::invalid_argument("display size must be positive");
  if (p_.interlaced && p_.height_px % 2 != 0) throw std::invalid_argument("an interlaced display needs an even line count");
  if (p_.vblank_lines < 0 || p_.hblank_px < 0) throw std::invalid_argument("blanking must not be negative");
  // One pixel time is period / (total lines * pixels per line) of a field.
  const stats::i128 num = static_cast<stats::i128>(p_.field_period.num) * des::Time::kTicksPerSecond;
  const stats::i128 den = static_cast<stats::i128>(total_lines_per_field()) * pixels_per_line() * p_.field_period.den;
  const stats::i128 g = gcd(num, den);
  k_ = num / g;
  d_ = den / g;
}

des::Time RasterTiming::field_start(int64_t field) const {
  if (noise_) return schedule_.at(field) + noise_->offset(field);
  return schedule_.at(field);
}

des::Time RasterTiming::end_slack() const {
  const int64_t last = slot(lines_per_field() - 1, p_.width_px - 1);
  return schedule_.nominal_period() - offset(last);
}

int64_t RasterTiming::noisy_index_at_or_after(des::Time t) const {
  const int64_t guess = schedule_.index_at_or_after(t);
  int64_t k = schedule_.index_at_or_after(t - noise_->offset(guess));
  while (field_start(k) < t) ++k;
  while (field_start(k - 1) >= t) --k;
  return k;
}

des::Time RasterTiming::offset(int64_t slot_times_px) const {
  // slot pixel times of period / (total lines * pixels per line) each, floored
  // to a tick in 128-bit arithmetic: exact, and identical for every field.
  return des::Time::ps(static_cast<int64_t>(static_cast<stats::i128>(slot_times_px) * k_ / d_));
}

des::Time RasterTiming::line_time(int64_t field, int j) const { return field_start(field) + offset(slot(j, 0)); }

des::Time RasterTiming::pixel_time(int64_t field, int j, int x) const { return field_start(field) + offset(slot(j, x)); }

stats::TickRun RasterTiming::photon_run(int64_t field, int j, int x, int64_t slot_step, uint64_t count) const {
  return stats::TickRun::make(field_start(field).ticks(), static_cast<stats::i128>(slot(j, x)) * k_,
                            static_cast<stats::i128>(slot_step) * k_, d_, count);
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
