#include "frame_stages/warp_clock.hpp"

#include <stdexcept>

namespace latsim::pipelines::frame_stages {

WarpClock::WarpClock(const display::RasterTiming& timing, int strips) : timing_(timing), strips_(strips) {
  if (strips < 1 || strips > timing.lines_per_field())
    throw std::invalid_argument("a field has between one strip and one strip per line");
}

int WarpClock::first_line(int strip) const {
  return static_cast<int>(static_cast<int64_t>(strip) * timing_.lines_per_field() / strips_);
}

des::Time WarpClock::deadline(Slot slot) const {
  if (strips_ == 1) return timing_.field_start(slot.field);
  return timing_.line_time(slot.field, first_line(slot.strip));
}

des::Time WarpClock::next_deadline(des::Time t) const {
  // Deadlines of field m all lie in [start(m), start(m + 1)): look in the
  // field holding t, then take the next field's first.
  const int64_t m = timing_.field_at_or_before(t);
  for (int s = 0; s < strips_; ++s) {
    const des::Time d = deadline(Slot{m, s});
    if (d >= t) return d;
  }
  return deadline(Slot{m + 1, 0});
}

WarpClock::Slot WarpClock::slot_of(des::Time d) const {
  const int64_t m = timing_.field_at_or_before(d);
  for (int s = strips_ - 1; s >= 0; --s)
    if (deadline(Slot{m, s}) <= d) return Slot{m, s};
  return Slot{m, 0};
}

int WarpClock::middle_line(int strip) const {
  const int a = first_line(strip);
  const int b = strip + 1 < strips_ ? first_line(strip + 1) : timing_.lines_per_field();
  return a + (b - a - 1) / 2;
}

}  // namespace latsim::pipelines::frame_stages
