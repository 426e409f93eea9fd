// Minimum-jerk movements: the profile, its peak speed, the rests and the
// motion phases it produces.
#include <catch2/catch.hpp>

#include <cmath>

#include "latsim/tracker/minimum_jerk.hpp"
#include "latsim/tracker/motion_phase.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using namespace latsim::tracker;
using latsim::des::Time;

namespace {


MinimumJerkParams thirty_degrees() {
  MinimumJerkParams p;
  p.amplitude_deg = 30.0;
  p.duration = Time::ms(500);
  p.rest = Time::ms(500);
  return p;
}

// Central difference of the angle about the axis, deg/s, over ±1 µs.
double speed_deg_s(const MinimumJerkMotion& m, Time t) {
  const Time h = Time::us(1);
  return (m.angle_deg_at(t + h) - m.angle_deg_at(t - h)) / (2.0 * h.to_seconds());
}

}  // namespace

TEST_CASE("the minimum-jerk profile peaks at 1.875 amplitude over duration", "[minimum_jerk]") {
  // s(τ) = 10τ³ − 15τ⁴ + 6τ⁵, s'(τ) = 30τ² − 60τ³ + 30τ⁴ = 30 τ² (1 − τ)²,
  // largest at τ = 1/2: 30 · 1/4 · 1/4 = 1.875. Peak speed = 1.875 · A / D
  // = 1.875 · 30 deg / 0.5 s = 112.5 deg/s, at rest + D/2 = 0.75 s.
  const MinimumJerkMotion m(thirty_degrees());
  const double peak = 1.875 * 30.0 / 0.5;
  CHECK(speed_deg_s(m, Time::ms(750)) == Approx(peak).epsilon(1e-6));
  // No instant of the movement is faster (0.1 ms grid).
  double fastest = 0.0;
  for (int us = 500'000; us <= 1'000'000; us += 100) fastest = std::max(fastest, std::abs(speed_deg_s(m, Time::us(us))));
  CHECK(fastest <= peak * (1.0 + 1e-9));
  // Half way in time is half way in angle: s(1/2) = 10/8 − 15/16 + 6/32 = 1/2.
  CHECK(m.angle_deg_at(Time::ms(750)) == Approx(15.0).epsilon(1e-12));
  CHECK(MinimumJerkMotion::profile(0.5) == Approx(0.5).epsilon(1e-15));
  // Starts and ends at rest: zero speed at both ends of the movement.
  CHECK(std::abs(speed_deg_s(m, Time::ms(500) + Time::us(1))) < 1e-6);
  CHECK(std::abs(speed_deg_s(m, Time::ms(1000) - Time::us(1))) < 1e-6);
}

TEST_CASE("the head is still during every rest", "[minimum_jerk]") {
  const MinimumJerkMotion m(thirty_degrees());
  // Rest before the first movement: the start pose exactly.
  for (int ms = 0; ms <= 500; ms += 50) CHECK(m.pose_at(Time::ms(ms)).orientation == m.pose_at(Time::zero()).orientation);
  // After movement 0 (ends at 1 s) the head rests at 30 degrees until 1.5 s.
  const auto held = m.pose_at(Time::ms(1000)).orientation;
  for (int ms = 1000; ms <= 1500; ms += 50) CHECK(m.pose_at(Time::ms(ms)).orientation == held);
  CHECK(angle_between(held, m.pose_at(Time::zero()).orientation) == Approx(30.0 * units::kRadPerDeg).epsilon(1e-12));
  // Movement 1 (1.5 s to 2 s) comes back: at 2 s the start pose again.
  CHECK(m.angle_deg_at(Time::ms(2000)) == Approx(0.0).margin(1e-12));
  CHECK(m.angle_deg_at(Time::ms(1750)) == Approx(15.0).epsilon(1e-12));
}

TEST_CASE("same-way movements keep turning", "[minimum_jerk]") {
  MinimumJerkParams p = thirty_degrees();
  p.alternate = false;
  const MinimumJerkMotion m(p);
  CHECK(m.angle_deg_at(Time::ms(2000)) == Approx(60.0).epsilon(1e-12));
  CHECK(m.angle_deg_at(Time::ms(2750)) == Approx(75.0).epsilon(1e-12));
  // 13 movements = 390 degrees: the orientation is 30 degrees from the start.
  const Time after13 = m.movement_start(12) + p.duration;
  CHECK(m.angle_deg_at(after13) == Approx(390.0).epsilon(1e-12));
  CHECK(angle_between(m.pose_at(after13).orientation, m.pose_at(Time::zero()).orientation) ==
        Approx(30.0 * units::kRadPerDeg).epsilon(1e-9));
}

TEST_CASE("minimum-jerk movements split into onset, steady and stop", "[minimum_jerk][motion_phase]") {
  // Speed (A/D) · 30 τ²(1 − τ)² with A/D = 60 deg/s crosses 40 deg/s where
  // τ(1 − τ) = sqrt(40 / 1800) = 0.14907: τ = (1 − sqrt(1 − 4 · 0.14907)) / 2
  // = 0.18237 and 0.81763, i.e. 91.2 ms and 408.8 ms into the movement
  // (movement 0 starts at 0.5 s). On the 5 ms grid the speed of an interval
  // is its mean, so the crossings are found within a step. The movement
  // starts where the head left rest (0.5 deg/s): the mean speeds of the
  // first intervals are 30 x 10 (0.01³ − 0)/5 ms = 0.06, 30 x 10 (0.02³ −
  // 0.01³)/5 ms = 0.42 and 1.14 deg/s (the τ⁴ and τ⁵ terms change them by
  // under 5 %), so the last interval at rest ends 10 ms in: onset from
  // 510 ms to 610 ms. The stop is the threshold's, 408.8 ms in: the first
  // interval below 40 deg/s starts at 910 ms.
  const MinimumJerkMotion m(thirty_degrees());
  MotionPhaseParams p;  // 40 deg/s, 100 ms window, 5 ms step, rest 0.5 deg/s
  MotionPhaseClassifier c(m, p);
  CHECK(c.phase_at(Time::ms(300)) == MotionPhase::Still);
  CHECK(c.phase_at(Time::ms(500 + 5)) == MotionPhase::Still);
  CHECK(c.phase_at(Time::ms(500 + 15)) == MotionPhase::Onset);
  CHECK(c.phase_at(Time::ms(500 + 105)) == MotionPhase::Onset);
  CHECK(c.phase_at(Time::ms(500 + 115)) == MotionPhase::Steady);
  CHECK(c.phase_at(Time::ms(500 + 400)) == MotionPhase::Steady);
  CHECK(c.phase_at(Time::ms(500 + 415)) == MotionPhase::Stop);
  CHECK(c.phase_at(Time::ms(500 + 500)) == MotionPhase::Stop);
  CHECK(c.phase_at(Time::ms(500 + 520)) == MotionPhase::Still);
  const auto starts = c.starts_until(Time::ms(1505));
  REQUIRE(starts.size() == 1);
  CHECK(starts[0] == Time::ms(510));
  // Movement 1 starts at 1.5 s: dated 1510 ms, before its threshold crossing.
  CHECK(c.starts_until(Time::ms(1550)).size() == 2);
}

TEST_CASE("a start out of slow drift keeps the threshold crossing", "[motion_phase]") {
  // Above the rest speed all the while (a constant 10 deg/s drift, then a
  // turn on top of it): nothing to date back to, the start is the crossing.
  MotionPhaseParams p;
  p.rest_deg_s = 0.5;
  MinimumJerkParams mj = thirty_degrees();
  const MinimumJerkMotion turn(mj);
  class Drifting final : public MotionSource {
   public:
    explicit Drifting(const MinimumJerkMotion& t) : t_(t) {}
    Pose pose_at(Time t) const override {
      Pose q = t_.pose_at(t);
      q.orientation = quat_from_rotation_vector(glm::dvec3(0.0, 10.0 * units::kRadPerDeg * t.to_seconds(), 0.0)) * q.orientation;
      return q;
    }
    std::string name() const override { return "drifting"; }

   private:
    const MinimumJerkMotion& t_;
  } drifting(turn);
  MotionPhaseClassifier c(drifting, p);
  // 10 + 60 · 30 τ²(1 − τ)² > 40 once τ(1 − τ) > sqrt(30 / 1800): τ = 0.1464, 73.2 ms in.
  const auto starts = c.starts_until(Time::ms(1000));
  REQUIRE(starts.size() == 1);
  CHECK(starts[0] >= Time::ms(570));
  CHECK(starts[0] <= Time::ms(575));
}

TEST_CASE("minimum-jerk settings are checked", "[minimum_jerk]") {
  MinimumJerkParams p = thirty_degrees();
  p.axis = {0.0, 0.0, 0.0};
  CHECK_THROWS_AS(MinimumJerkMotion(p), std::invalid_argument);
  p = thirty_degrees();
  p.duration = Time::zero();
  CHECK_THROWS_AS(MinimumJerkMotion(p), std::invalid_argument);
}
