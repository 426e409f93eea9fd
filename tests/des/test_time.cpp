// Time arithmetic, conversions and exact periodic schedules.
#include <catch2/catch.hpp>

#include <limits>

#include "latsim/des/time.hpp"

using latsim::des::PeriodicSchedule;
using latsim::des::RationalSeconds;
using latsim::des::Time;
using latsim::des::TimeOverflow;

TEST_CASE("time factories count picoseconds", "[time]") {
  CHECK(Time::ns(1).ticks() == 1'000);
  CHECK(Time::us(3).ticks() == 3'000'000);
  CHECK(Time::ms(16).ticks() == 16'000'000'000);
  CHECK(Time::s(2).ticks() == 2'000'000'000'000);
  CHECK(Time::from_seconds(0.5) == Time::ms(500));
  CHECK(Time::from_ms(16.7) == Time::us(16'700));
  CHECK(Time::from_us(0.001) == Time::ns(1));
  CHECK(Time::from_us(1e-6) == Time::ps(1));
  CHECK(Time::ms(3) + Time::us(5) == Time::ps(3'005'000'000));
  CHECK(Time::ms(3) / Time::us(7) == 428);
  CHECK(Time::ms(3) % Time::us(7) == Time::us(4));
  CHECK(Time::s(1) * 3 == 3 * Time::s(1));
}

TEST_CASE("time overflow is reported, never wrapped", "[time]") {
  const Time big = Time::max();
  CHECK_THROWS_AS(big + Time::ps(1), TimeOverflow);
  CHECK_THROWS_AS(-big - Time::ps(2), TimeOverflow);
  CHECK_THROWS_AS(big * 2, TimeOverflow);
  CHECK_THROWS_AS(Time::s(10'000'000), TimeOverflow);  // beyond ~106 days
  CHECK_THROWS_AS(Time::ms(std::numeric_limits<int64_t>::max() / 1000), TimeOverflow);
  CHECK_THROWS_AS(Time::from_seconds(1e300), TimeOverflow);
  CHECK_THROWS_AS(Time::from_seconds(-1e300), TimeOverflow);
  CHECK_THROWS_AS(Time::from_seconds(std::numeric_limits<double>::quiet_NaN()), TimeOverflow);
  CHECK_THROWS_AS(Time::from_seconds(std::numeric_limits<double>::infinity()), TimeOverflow);
  CHECK_THROWS_AS(Time::from_ms(1e20), TimeOverflow);
  CHECK_THROWS_AS(Time::ms(1) / Time::zero(), std::domain_error);
  CHECK_NOTHROW(Time::s(9'000'000) + Time::s(200'000));
}

TEST_CASE("periodic schedule has zero drift after a billion NTSC fields", "[time]") {
  const RationalSeconds field = RationalSeconds::period_of_hz(60000, 1001);
  CHECK(field.num == 1001);
  CHECK(field.den == 60000);

  // A billion fields (193 days) exceed the int64 picosecond range from 0 ...
  const PeriodicSchedule from_zero(Time::zero(), field);
  CHECK_THROWS_AS(from_zero.at(1'000'000'000), TimeOverflow);
  // ... but the schedule still computes them exactly from a negative origin.
  // By hand: 1e9 * 1001 / 60000 s = 1001e17 / 6 ps = 16683333333333333333 ps
  // (remainder 2), plus the origin -9e18 ps.
  const PeriodicSchedule sched(Time::s(-9'000'000), field);
  const int64_t k = 1'000'000'000;
  CHECK(sched.at(k).ticks() == 7'683'333'333'333'333'333);
  CHECK(sched.at(k) - sched.at(k - 1) == Time::ps(16'683'333'333));  // floor steps: 16683333333 or ...334
  CHECK(sched.at(3) - sched.at(0) == Time::ps(50'050'000'000));      // 3 * 1001/60000 s exactly
  // By hand from zero: 1e8 fields = 1001e16/6 ps = 1668333333333333333 ps (remainder 2).
  CHECK(from_zero.at(100'000'000).ticks() == 1'668'333'333'333'333'333);

  // Accumulating the rounded period would have drifted by a third of a tick per field.
  // (Added in two halves: the whole product alone would leave the range.)
  const Time accumulated = Time::s(-9'000'000) + sched.nominal_period() * (k / 2) + sched.nominal_period() * (k / 2);
  CHECK(accumulated != sched.at(k));
  CHECK(sched.at(k) - accumulated == Time::ps(333'333'333));

  for (const int64_t i : {k, k - 1, int64_t{-5}, int64_t{0}, int64_t{123'456'789}}) {
    const Time t = sched.at(i);
    CHECK(sched.index_at_or_after(t) == i);
    CHECK(sched.index_at_or_before(t) == i);
    CHECK(sched.index_at_or_after(t + Time::ps(1)) == i + 1);
    CHECK(sched.index_at_or_before(t - Time::ps(1)) == i - 1);
    CHECK(sched.index_at_or_before(sched.at(i + 1) - Time::ps(1)) == i);
  }
}

TEST_CASE("periodic schedule rejects bad periods", "[time]") {
  CHECK_THROWS_AS(PeriodicSchedule(Time::zero(), RationalSeconds{0, 1}), std::invalid_argument);
  CHECK_THROWS_AS(PeriodicSchedule(Time::zero(), RationalSeconds{1, -60}), std::invalid_argument);
  CHECK_THROWS_AS(RationalSeconds::period_of_hz(0), std::invalid_argument);
  const PeriodicSchedule huge(Time::zero(), RationalSeconds{std::numeric_limits<int64_t>::max(), 1});
  CHECK_THROWS_AS(huge.at(std::numeric_limits<int64_t>::max()), TimeOverflow);
}
