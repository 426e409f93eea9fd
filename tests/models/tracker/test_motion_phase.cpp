// Motion phases: onset and stop windows after the angular speed crosses the
// threshold, steady motion and rest in between.
#include <catch2/catch.hpp>

#include <memory>

#include "latsim/tracker/motion_phase.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using namespace latsim::tracker;
using latsim::des::Time;

namespace {


/// Still until 1 s, a yaw at 90 deg/s from 1 s to 3 s (slerped between
/// samples 45 degrees apart), still again after 3 s.
TraceMotion turn_and_stop() {
  auto trace = std::make_shared<Trace>();
  trace->samples.push_back({Time::zero(), Pose{}});
  for (int i = 0; i <= 4; ++i)
    trace->samples.push_back({Time::ms(1000) + Time::ms(500) * i, Pose{{}, quat_from_yaw_pitch(45.0 * i * units::kRadPerDeg, 0.0)}});
  trace->samples.push_back({Time::s(10), trace->samples.back().pose});
  return TraceMotion(trace, Time::zero(), false);
}

}  // namespace

TEST_CASE("phases follow the threshold crossings of the angular speed", "[motion_phase]") {
  const TraceMotion motion = turn_and_stop();
  MotionPhaseParams p;
  p.threshold_deg_s = 30.0;
  p.window = Time::ms(200);
  p.step = Time::ms(5);
  MotionPhaseClassifier c(motion, p);
  // Grid intervals [k 5 ms, (k + 1) 5 ms): the start at 1 s and the stop at
  // 3 s fall on grid points, so the crossings are exact.
  CHECK(c.phase_at(Time::ms(500)) == MotionPhase::Still);
  CHECK(c.phase_at(Time::ms(999)) == MotionPhase::Still);
  CHECK(c.phase_at(Time::ms(1000)) == MotionPhase::Onset);
  CHECK(c.phase_at(Time::ms(1199)) == MotionPhase::Onset);
  CHECK(c.phase_at(Time::ms(1200)) == MotionPhase::Steady);
  CHECK(c.phase_at(Time::ms(2999)) == MotionPhase::Steady);
  CHECK(c.phase_at(Time::ms(3000)) == MotionPhase::Stop);
  CHECK(c.phase_at(Time::ms(3199)) == MotionPhase::Stop);
  CHECK(c.phase_at(Time::ms(3200)) == MotionPhase::Still);
  CHECK(c.transitions() == 2);
  // Earlier instants may be asked again after later ones.
  CHECK(c.phase_at(Time::ms(1100)) == MotionPhase::Onset);
  CHECK(c.phase_at(-Time::ms(5)) == MotionPhase::Still);
}

TEST_CASE("a threshold above the speed sees no movement at all", "[motion_phase]") {
  const TraceMotion motion = turn_and_stop();
  MotionPhaseParams p;
  p.threshold_deg_s = 90.5;  // the turn runs at exactly 90 deg/s
  MotionPhaseClassifier c(motion, p);
  for (int ms = 0; ms < 5000; ms += 50) CHECK(c.phase_at(Time::ms(ms)) == MotionPhase::Still);
  CHECK(c.transitions() == 0);
}

TEST_CASE("motion at time zero is steady, not an onset", "[motion_phase]") {
  const ConstantAngularVelocity spin(Pose{}, {0, 1, 0}, 100.0);
  MotionPhaseClassifier c(spin, MotionPhaseParams{});
  CHECK(c.phase_at(Time::zero()) == MotionPhase::Steady);
  CHECK(c.phase_at(Time::s(3600)) == MotionPhase::Steady);
  CHECK(c.transitions() == 0);
  CHECK(phase_name(MotionPhase::Onset) == "onset");
}

TEST_CASE("motion phase parameters are checked", "[motion_phase]") {
  const StillMotion still(Pose{});
  MotionPhaseParams p;
  p.window = Time::zero();
  CHECK_THROWS_AS(MotionPhaseClassifier(still, p), std::invalid_argument);
  p = MotionPhaseParams{};
  p.threshold_deg_s = -1.0;
  CHECK_THROWS_AS(MotionPhaseClassifier(still, p), std::invalid_argument);
}
