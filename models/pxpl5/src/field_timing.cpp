#include "latsim/pxpl5/field_timing.hpp"

#include <stdexcept>

namespace latsim::pxpl5 {

FieldTiming::FieldTiming(des::Time t0, des::RationalSeconds period, int vblank_lines, int active_lines,
                         bool interlaced)
    : schedule_(t0, period), vblank_lines_(vblank_lines), active_lines_(active_lines), interlaced_(interlaced) {
  if (vblank_lines < 0 || active_lines <= 0) throw std::invalid_argument("FieldTiming: bad line counts");
}

int64_t FieldTiming::field_after(des::Time t) const {
  const int64_t k = schedule_.index_at_or_after(t);
  return schedule_.at(k) == t ? k + 1 : k;
}

des::Time FieldTiming::line_time(int64_t field, int line) const {
  // Offset from the field's own retrace, so the exact rational period is
  // never accumulated; 128-bit keeps slot * ticks from overflowing.
  const des::Time start = retrace(field);
  const __int128 span = (retrace(field + 1) - start).ticks();
  const __int128 slot = vblank_lines_ + line;
  const auto offset = static_cast<int64_t>(span * slot / (vblank_lines_ + active_lines_));
  return start + des::Time::ps(offset);
}

}  // namespace latsim::pxpl5
