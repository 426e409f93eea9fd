// Motion sources: still, constant rotation, sinusoid, polyline walk.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "latsim/tracker/motion_source.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using namespace latsim::tracker;
using latsim::des::Time;

namespace {


void check_position(const Pose& p, glm::dvec3 expected_m) {
  CHECK(p.position_m.x == Approx(expected_m.x).margin(1e-12));
  CHECK(p.position_m.y == Approx(expected_m.y).margin(1e-12));
  CHECK(p.position_m.z == Approx(expected_m.z).margin(1e-12));
}

void check_forward(const Pose& p, glm::dvec3 expected) {
  const glm::dvec3 f = forward_of(p.orientation);
  CHECK(f.x == Approx(expected.x).margin(1e-12));
  CHECK(f.y == Approx(expected.y).margin(1e-12));
  CHECK(f.z == Approx(expected.z).margin(1e-12));
}

}  // namespace

TEST_CASE("still motion never changes", "[motion]") {
  const Pose pose{{1.0, 1.7, -2.0}, quat_from_yaw_pitch(0.3, 0.1)};
  const StillMotion still(pose);
  CHECK(still.is_still());
  for (Time t : {Time::zero(), Time::ms(17), Time::s(100000)}) {
    const Pose p = still.pose_at(t);
    CHECK(p.position_m == pose.position_m);
    CHECK(p.orientation == pose.orientation);
  }
}

TEST_CASE("constant angular velocity turns by rate * t", "[motion]") {
  const Pose start{{0.0, 1.6, 0.0}, quat_from_yaw_pitch(0.2, -0.1)};
  const ConstantAngularVelocity spin(start, {0.0, 2.0, 0.0}, 100.0);
  CHECK_FALSE(spin.is_still());
  CHECK(angle_between(spin.pose_at(Time::zero()).orientation, start.orientation) == 0.0);
  CHECK(angle_between(spin.pose_at(Time::ms(500)).orientation, start.orientation) ==
        Approx(50.0 * units::kRadPerDeg).epsilon(1e-12));
  // Rotation is about world y: the yaw grows, the pitch stays.
  CHECK(yaw_of(spin.pose_at(Time::ms(100)).orientation) == Approx(0.2 + 10.0 * units::kRadPerDeg).epsilon(1e-12));
  CHECK(pitch_of(spin.pose_at(Time::ms(100)).orientation) == Approx(-0.1).epsilon(1e-12));
  // Three hours and a quarter second: 1080025 degrees = 3000 turns + 25 degrees.
  const Time late = Time::s(3 * 3600) + Time::ms(250);
  CHECK(angle_between(spin.pose_at(late).orientation, start.orientation) ==
        Approx(25.0 * units::kRadPerDeg).epsilon(1e-9));
  // 573 ps at 100 deg/s is about 1e-9 rad.
  const double tiny_rad = 100.0 * units::kRadPerDeg * 573e-12;
  CHECK(angle_between(spin.pose_at(Time::ps(573)).orientation, start.orientation) ==
        Approx(tiny_rad).epsilon(1e-7));
  CHECK(spin.pose_at(late).position_m == start.position_m);
}

TEST_CASE("constant angular velocity rejects a zero axis", "[motion]") {
  CHECK_THROWS_AS(ConstantAngularVelocity(Pose{}, {0.0, 0.0, 0.0}, 10.0), std::invalid_argument);
}

TEST_CASE("sinusoidal motion peaks at the quarter periods", "[motion]") {
  SinusoidParams p;
  p.yaw_amplitude_deg = 30.0;
  p.yaw_frequency_hz = 0.5;
  p.pitch_amplitude_deg = 10.0;
  p.pitch_frequency_hz = 0.25;
  const SinusoidalMotion m(p);
  const auto yaw_deg = [&](Time t) { return yaw_of(m.pose_at(t).orientation) / units::kRadPerDeg; };
  const auto pitch_deg = [&](Time t) { return pitch_of(m.pose_at(t).orientation) / units::kRadPerDeg; };
  CHECK(yaw_deg(Time::zero()) == Approx(0.0).margin(1e-12));
  CHECK(yaw_deg(Time::ms(500)) == Approx(30.0).epsilon(1e-12));
  CHECK(yaw_deg(Time::ms(1500)) == Approx(-30.0).epsilon(1e-12));
  CHECK(pitch_deg(Time::s(1)) == Approx(10.0).epsilon(1e-12));
  CHECK(pitch_deg(Time::s(3)) == Approx(-10.0).epsilon(1e-12));
  // The peak is a maximum: a millisecond either side is lower.
  CHECK(yaw_deg(Time::ms(499)) < yaw_deg(Time::ms(500)));
  CHECK(yaw_deg(Time::ms(501)) < yaw_deg(Time::ms(500)));
  // Still exact after an hour.
  CHECK(yaw_deg(Time::s(3600) + Time::ms(500)) == Approx(30.0).epsilon(1e-10));
}

TEST_CASE("phase shifts the sinusoid", "[motion]") {
  SinusoidParams p;
  p.yaw_amplitude_deg = 20.0;
  p.yaw_frequency_hz = 1.0;
  p.yaw_phase_deg = 90.0;
  const SinusoidalMotion m(p);
  CHECK(m.yaw_rad_at(Time::zero()) == Approx(20.0 * units::kRadPerDeg).epsilon(1e-14));
  CHECK_FALSE(m.is_still());
  CHECK(SinusoidalMotion(SinusoidParams{}).is_still());
}

TEST_CASE("polyline walk follows the path at constant speed", "[motion]") {
  WalkParams p;
  p.points_m = {{0.0, 1.7, 0.0}, {3.0, 1.7, 0.0}, {3.0, 1.7, 4.0}};
  p.speed_m_s = 1.0;
  const PolylineWalk walk(p);
  CHECK(walk.path_length_m() == Approx(7.0));
  check_position(walk.pose_at(Time::zero()), {0.0, 1.7, 0.0});
  check_position(walk.pose_at(Time::ms(1500)), {1.5, 1.7, 0.0});
  check_position(walk.pose_at(Time::s(3)), {3.0, 1.7, 0.0});  // the corner
  check_position(walk.pose_at(Time::s(5)), {3.0, 1.7, 2.0});
  check_position(walk.pose_at(Time::s(7)), {3.0, 1.7, 4.0});
  check_position(walk.pose_at(Time::s(60)), {3.0, 1.7, 4.0});  // clamped at the end
  // Facing the direction of travel: +x on the first leg, +z on the second.
  check_forward(walk.pose_at(Time::s(1)), {1.0, 0.0, 0.0});
  check_forward(walk.pose_at(Time::s(4)), {0.0, 0.0, 1.0});
}

TEST_CASE("walk turns its corners at the turn rate, centred on the corner", "[motion]") {
  // A right-angle corner at 3 m, walked at 1 m/s with 90 deg/s: the turn
  // takes 1 s, from 2.5 s to 3.5 s; halfway through the corner the head
  // faces 45 degrees between +x and +z.
  WalkParams p;
  p.points_m = {{0.0, 1.7, 0.0}, {3.0, 1.7, 0.0}, {3.0, 1.7, 4.0}};
  p.speed_m_s = 1.0;
  p.turn_rate_deg_s = 90.0;
  const PolylineWalk walk(p);
  check_forward(walk.pose_at(Time::ms(2499)), {1.0, 0.0, 0.0});
  check_forward(walk.pose_at(Time::s(3)), {std::sqrt(0.5), 0.0, std::sqrt(0.5)});
  check_forward(walk.pose_at(Time::ms(3501)), {0.0, 0.0, 1.0});
  check_position(walk.pose_at(Time::s(3)), {3.0, 1.7, 0.0});  // the path itself is unchanged
  // Millisecond by millisecond, the head never turns faster than 90 deg/s,
  // and in the middle of the turn it turns at exactly that rate.
  double max_step_deg = 0.0;
  for (int64_t ms = 0; ms < 7000; ++ms) {
    const glm::dquat a = walk.pose_at(Time::ms(ms)).orientation, b = walk.pose_at(Time::ms(ms + 1)).orientation;
    const double step = units::rad_to_deg(2.0 * std::acos(std::min(1.0, std::abs(glm::dot(a, b)))));
    max_step_deg = std::max(max_step_deg, step);
  }
  CHECK(max_step_deg <= 0.09 + 1e-6);
  CHECK(max_step_deg >= 0.09 - 1e-6);
  // Turned at once, the whole corner falls between two milliseconds.
  p.turn_rate_deg_s = 0.0;
  const PolylineWalk sharp(p);
  const glm::dquat a = sharp.pose_at(Time::ms(2999)).orientation, b = sharp.pose_at(Time::ms(3001)).orientation;
  CHECK(units::rad_to_deg(2.0 * std::acos(std::min(1.0, std::abs(glm::dot(a, b))))) == Approx(90.0));
}

TEST_CASE("walk shortens a turn that would not fit its legs", "[motion]") {
  // Legs of 0.4 m and 4 m: the 1 m turn is cut to 0.2 m either side of the corner.
  WalkParams p;
  p.points_m = {{0.0, 0.0, 0.0}, {0.4, 0.0, 0.0}, {0.4, 0.0, 4.0}};
  const PolylineWalk walk(p);
  check_forward(walk.pose_at(Time::ms(199)), {1.0, 0.0, 0.0});
  check_forward(walk.pose_at(Time::ms(601)), {0.0, 0.0, 1.0});
  check_forward(walk.pose_at(Time::ms(400)), {std::sqrt(0.5), 0.0, std::sqrt(0.5)});
}

TEST_CASE("looping walk closes the polygon and keeps its speed", "[motion]") {
  WalkParams p;
  p.points_m = {{0.0, 0.0, 0.0}, {3.0, 0.0, 0.0}, {3.0, 0.0, 4.0}};
  p.speed_m_s = 2.0;
  p.loop = true;
  const PolylineWalk walk(p);
  CHECK(walk.path_length_m() == Approx(12.0));
  // 4.75 s at 2 m/s = 9.5 m: 2.5 m into the closing 5 m leg back to the origin.
  check_position(walk.pose_at(Time::ms(4750)), {1.5, 0.0, 2.0});
  check_forward(walk.pose_at(Time::ms(4750)), {-0.6, 0.0, -0.8});
  // One lap is 6 s.
  check_position(walk.pose_at(Time::ms(6750)), {1.5, 0.0, 0.0});
}

TEST_CASE("walk keeps a fixed orientation when not facing the direction", "[motion]") {
  WalkParams p;
  p.points_m = {{0.0, 0.0, 0.0}, {0.0, 0.0, -10.0}};
  p.face_direction = false;
  p.orientation = quat_from_yaw_pitch(1.0, 0.0);
  const PolylineWalk walk(p);
  CHECK(walk.pose_at(Time::s(3)).orientation == p.orientation);
  check_position(walk.pose_at(Time::s(3)), {0.0, 0.0, -3.0});
}
