#include "latsim/display/persistence.hpp"

#include <stdexcept>

namespace latsim::display {

namespace {

using Mode = PersistenceParams::Mode;

des::Time half(des::Time t) { return des::Time::ps(t.ticks() / 2); }

}  // namespace

Persistence::Persistence(PersistenceParams params, const RasterTiming& timing) : params_(params), timing_(timing) {
  if (params_.response < des::Time::zero()) throw std::invalid_argument("pixel response time must not be negative");
  if (params_.mode == Mode::rolling || params_.mode == Mode::global) {
    // A row is written once per frame; a longer flash would overlap the next one.
    const des::Time frame = timing.field_start(timing.fields_per_frame()) - timing.field_start(0);
    if (params_.lit <= des::Time::zero() || params_.lit > frame)
      throw std::invalid_argument("a low-persistence flash must last more than 0 and at most one frame period");
  }
}

LitInterval Persistence::lit(int64_t field, des::Time written) const {
  switch (params_.mode) {
    case Mode::impulse:
      return {written, des::Time::zero()};
    case Mode::full: {
      // Held until the same row is written again, one frame (fields_per_frame fields) later.
      const int64_t fpf = timing_.fields_per_frame();
      const des::Time hold = timing_.field_start(field + fpf) - timing_.field_start(field);
      return {written + half(params_.response), hold};
    }
    case Mode::rolling:
      return {written + params_.response, params_.lit};
    case Mode::global:
      // Blanking sits at the start of each field, so the last active row of
      // field k has been written when field k + 1 begins.
      return {timing_.field_start(field + 1) + params_.response, params_.lit};
  }
  return {written, des::Time::zero()};
}

stats::TickRun Persistence::photons(int64_t field, const stats::TickRun& written) const {
  const des::Time first = des::Time::ps(written.base);
  const des::Time middle = lit(field, first).middle();
  if (params_.mode == Mode::global) return stats::TickRun::make(middle.ticks(), 0, 0, 1, written.count);
  // Every other mode lights a pixel a fixed time after its write.
  return written.shifted((middle - first).ticks());
}

}  // namespace latsim::display
