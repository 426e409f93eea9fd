// Lit intervals of the persistence model against hand-computed instants.
#include <catch2/catch.hpp>

#include <stdexcept>

#include "latsim/display/persistence.hpp"

using latsim::des::RationalSeconds;
using latsim::des::Time;
using latsim::display::LitInterval;
using latsim::display::Persistence;
using latsim::display::PersistenceParams;
using latsim::display::RasterParams;
using latsim::display::RasterTiming;
using Mode = PersistenceParams::Mode;

namespace {

// 62.5 Hz = exactly 16 ms per field; 160 lines without blanking, so line j of
// field k is written at 16k + 0.1j ms.
RasterTiming timing_16ms(bool interlaced = false) {
  RasterParams p;
  p.field_period = RationalSeconds::period_of_hz(125, 2);
  p.interlaced = interlaced;
  p.width_px = 100;
  p.height_px = 160;
  p.vblank_lines = 0;
  p.hblank_px = 0;
  return RasterTiming(p);
}

PersistenceParams params(Mode mode, double lit_ms, double response_ms) {
  PersistenceParams p;
  p.mode = mode;
  p.lit = Time::from_ms(lit_ms);
  p.response = Time::from_ms(response_ms);
  return p;
}

}  // namespace

TEST_CASE("persistence: an impulse display lights a pixel at its scanout instant and for no time") {
  const RasterTiming t = timing_16ms();
  const Persistence p(PersistenceParams{}, t);
  CHECK_FALSE(p.configured());
  const Time w = t.line_time(3, 40);  // 48 ms + 4 ms
  CHECK(w == Time::ms(52));
  const LitInterval lit = p.lit(3, w);
  CHECK(lit.on == w);
  CHECK(lit.duration == Time::zero());
  CHECK(lit.middle() == w);
}

TEST_CASE("persistence: full persistence holds a frame and crosses half way through the response") {
  const RasterTiming t = timing_16ms();
  const Persistence p(params(Mode::full, 0, 4), t);
  CHECK(p.configured());
  // Written at 52 ms; a 4 ms transition crosses 50 % at 54 ms; held 16 ms; middle 62 ms.
  const LitInterval lit = p.lit(3, Time::ms(52));
  CHECK(lit.on == Time::ms(54));
  CHECK(lit.duration == Time::ms(16));
  CHECK(lit.middle() == Time::ms(62));
}

TEST_CASE("persistence: full persistence on an interlaced display holds a row for two fields") {
  const RasterTiming t = timing_16ms(true);
  const Persistence p(params(Mode::full, 0, 0), t);
  const LitInterval lit = p.lit(5, t.line_time(5, 0));
  CHECK(lit.duration == Time::ms(32));
  CHECK(lit.middle() == Time::ms(80 + 16));
}

TEST_CASE("persistence: full persistence at 59.94 Hz holds exactly one field period to the tick") {
  RasterParams rp;
  rp.field_period = RationalSeconds::period_of_hz(60000, 1001);
  const RasterTiming t(rp);
  const Persistence p(params(Mode::full, 0, 0), t);
  // 1001/60 ms = 16.68333... ms: each hold is that period floored or ceiled to a picosecond.
  for (int64_t k : {0, 1, 2, 1000003}) {
    const Time d = p.lit(k, t.line_time(k, 0)).duration;
    CHECK((d == Time::ps(16'683'333'333) || d == Time::ps(16'683'333'334)));
  }
}

TEST_CASE("persistence: a rolling flash starts once each row has settled") {
  const RasterTiming t = timing_16ms();
  const Persistence p(params(Mode::rolling, 2, 0.5), t);
  // Row 40 of field 3 written at 52 ms: lit [52.5, 54.5], middle 53.5 ms.
  const LitInterval lit = p.lit(3, t.line_time(3, 40));
  CHECK(lit.on == Time::from_ms(52.5));
  CHECK(lit.duration == Time::ms(2));
  CHECK(lit.middle() == Time::from_ms(53.5));
  // Row 0 flashes 4 ms earlier: rolling keeps the scanout's stagger.
  CHECK(p.lit(3, t.line_time(3, 0)).middle() == Time::from_ms(49.5));
}

TEST_CASE("persistence: a global flash lights every row of a field at once after the last row is written") {
  const RasterTiming t = timing_16ms();
  const Persistence p(params(Mode::global, 2, 0.5), t);
  // Field 3 is written during [48, 64) ms; the flash is [64.5, 66.5] for every row.
  for (int j : {0, 80, 159}) {
    const LitInterval lit = p.lit(3, t.line_time(3, j));
    CHECK(lit.on == Time::from_ms(64.5));
    CHECK(lit.middle() == Time::from_ms(65.5));
  }
}

TEST_CASE("persistence: ten hours of fields keep exact flash instants") {
  const RasterTiming t = timing_16ms();
  const Persistence p(params(Mode::global, 2, 0), t);
  // 10 h at 62.5 Hz = 2,250,000 fields; field k flashes at 16 (k + 1) ms exactly.
  const int64_t k = 2'250'000;
  CHECK(p.lit(k, t.line_time(k, 7)).on == Time::ms(16 * (k + 1)));
}

TEST_CASE("persistence: a flash of no length or longer than a frame, or a negative response, is rejected") {
  const RasterTiming t = timing_16ms();
  CHECK_THROWS_AS(Persistence(params(Mode::rolling, 0, 0), t), std::invalid_argument);
  CHECK_THROWS_AS(Persistence(params(Mode::global, 16.001, 0), t), std::invalid_argument);
  CHECK_NOTHROW(Persistence(params(Mode::global, 16, 0), t));
  CHECK_THROWS_AS(Persistence(params(Mode::full, 0, -1), t), std::invalid_argument);
}
