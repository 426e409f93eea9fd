// The EDCA backoff counter: one decrement per idle slot boundary from the end
// of AIFS, the first at that end itself, frozen while the medium is busy.
#include <catch2/catch.hpp>

#include "latsim/radio/edca.hpp"

using latsim::des::RandomStream;
using latsim::des::Time;
using namespace latsim::radio;

TEST_CASE("the default EDCA parameter set of an OFDM PHY") {
  const EdcaParams be = EdcaParams::for_category("BE");
  CHECK((be.aifsn == 3 && be.cw_min == 15 && be.cw_max == 1023 && be.txop_limit == Time::zero()));
  const EdcaParams vi = EdcaParams::for_category("VI");
  CHECK((vi.aifsn == 2 && vi.cw_min == 7 && vi.cw_max == 15 && vi.txop_limit == Time::us(3008)));
  CHECK_THROWS(EdcaParams::for_category("XX"));
}

TEST_CASE("a counter frozen by a busy medium resumes where it stopped") {
  RandomStream stream(3, "backoff");
  Backoff b(EdcaParams{3, 1023, 1023, Time::zero()}, Time::us(9));
  // Draw until the counter is at least 3 (the derivation below needs it).
  do b.draw(Time::zero(), stream);
  while (b.slots() < 3);
  const int n = b.slots();
  // Idle since 100 us: AIFS = 3 slots after it, so boundaries at 127, 136, 145 us ...
  const Time access = Time::us(100);
  CHECK(b.expiry(access) == Time::us(127 + 9 * n));
  // The medium turns busy at 148 us: boundaries 127, 136, 145 have passed.
  b.count_down(access, Time::us(148));
  CHECK(b.slots() == n - 3);
  // Idle again from 500 us: it counts from AIFS after that, not from its old start.
  CHECK(b.expiry(Time::us(500)) == Time::us(527 + 9 * (n - 3)));
}

TEST_CASE("a frame for an empty queue goes at the next boundary on an idle medium, else draws") {
  RandomStream stream(1, "backoff");
  Backoff idle(EdcaParams{3, 15, 1023, Time::zero()}, Time::us(9));
  // Idle since 0: AIFS ends at 27 us; at 100 us the next boundary is 27 + 9 * 9 = 108 us.
  idle.on_arrival(Time::zero(), Time::us(100), false, stream);
  CHECK(idle.slots() == 0);
  CHECK(idle.expiry(Time::zero()) == Time::us(108));
  // Exactly on a boundary (99 us = 27 + 8 * 9): the next one, 108 us.
  Backoff on_boundary(EdcaParams{3, 15, 1023, Time::zero()}, Time::us(9));
  on_boundary.on_arrival(Time::zero(), Time::us(99), false, stream);
  CHECK(on_boundary.expiry(Time::zero()) == Time::us(108));
  // Before AIFS has ended: at its end.
  Backoff early(EdcaParams{3, 15, 1023, Time::zero()}, Time::us(9));
  early.on_arrival(Time::zero(), Time::us(5), false, stream);
  CHECK(early.expiry(Time::zero()) == Time::us(27));
  // Busy medium: a counter is drawn (CW 0: zero slots, counted from now).
  Backoff busy(EdcaParams{3, 0, 0, Time::zero()}, Time::us(9));
  busy.on_arrival(Time::zero(), Time::us(100), true, stream);
  CHECK(busy.start() == Time::us(100));
}

TEST_CASE("the contention window doubles to its maximum and resets") {
  Backoff b(EdcaParams{3, 15, 1023, Time::zero()}, Time::us(9));
  b.double_cw();
  CHECK(b.cw() == 31);
  for (int i = 0; i < 10; ++i) b.double_cw();
  CHECK(b.cw() == 1023);
  b.reset_cw();
  CHECK(b.cw() == 15);
}
