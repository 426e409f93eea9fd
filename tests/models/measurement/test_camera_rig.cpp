// The simulated camera rig: what a frame sees of a lit pixel, and the
// estimate of a pure delay at 120, 240 and 1000 frames per second.
#include <catch2/catch.hpp>

#include <cmath>
#include <numeric>

#include "latsim/des/random.hpp"
#include "latsim/measurement/camera_rig.hpp"
#include "latsim/tracker/minimum_jerk.hpp"

using namespace latsim;
using latsim::des::Time;

TEST_CASE("a frame sees the lit angles weighted by how long each is lit", "[camera_rig]") {
  const measurement::DisplaySignal held({{Time::zero(), Time::ms(10), 1.0}, {Time::ms(10), Time::ms(20), 3.0}});
  CHECK(*held.seen(Time::ms(5), Time::ms(15)) == Approx(2.0));    // 5 ms of each
  CHECK(*held.seen(Time::ms(8), Time::ms(18)) == Approx(2.6));    // 2 ms of 1, 8 ms of 3
  CHECK(*held.seen(Time::ms(12), Time::ms(12)) == Approx(3.0));   // a zero exposure reads the lit value
  CHECK_FALSE(held.seen(Time::ms(25), Time::ms(30)).has_value());
  const measurement::DisplaySignal flashes({{Time::ms(2), Time::ms(2), 1.0}, {Time::ms(12), Time::ms(12), 5.0}});
  CHECK(*flashes.seen(Time::zero(), Time::ms(20)) == Approx(3.0));
  CHECK_FALSE(flashes.seen(Time::ms(3), Time::ms(10)).has_value());
  // Angles are unwrapped within an exposure: 179 and −179 degrees average to 180.
  const measurement::DisplaySignal wrap({{Time::zero(), Time::ms(10), 179.0}, {Time::ms(10), Time::ms(20), -179.0}});
  CHECK(std::abs(*wrap.seen(Time::ms(5), Time::ms(15))) == Approx(180.0));
}

TEST_CASE("the rig measures a pure delay within half a camera frame", "[camera_rig]") {
  // The object turns by minimum-jerk movements of 30 degrees in 0.5 s with
  // rests of 0.4137 s (a period no camera frame divides, so every movement
  // meets the camera at another phase); the display shows exactly the
  // object's angle d = 37.3 ms late. Frame counting dates each start to the
  // frame it is first seen in, so each estimate is off by less than one
  // frame (half a frame per instant, the rig's stated resolution) and their
  // mean converges on d; the trajectory shift interpolates between frames and
  // is within half a frame on every movement.
  tracker::MinimumJerkParams mj;
  mj.amplitude_deg = 30.0;
  mj.duration = Time::ms(500);
  mj.rest = Time::us(413'700);
  const tracker::MinimumJerkMotion object(mj);
  const Time d = Time::us(37'300);
  const measurement::ObjectSignal real([&](Time t) { return object.angle_deg_at(t); });
  const measurement::ObjectSignal shown([&](Time t) { return object.angle_deg_at(t - d); });
  for (const int fps : {120, 240, 1000}) {
    CAPTURE(fps);
    const des::RationalSeconds period = des::RationalSeconds::period_of_hz(fps);
    des::RandomStream stream(1, "test.camera");
    const Time phase = Time::ps(static_cast<int64_t>(stream.uniform_int(static_cast<uint64_t>(1'000'000'000'000 / fps))));
    const des::PeriodicSchedule camera(phase, period);
    const double frame_ms = 1000.0 / fps;
    const measurement::RigResult r =
        measurement::film(real, shown, camera, camera.nominal_period(), Time::s(20), measurement::CameraRigParams{});
    CHECK(r.resolution_ms == Approx(frame_ms / 2));
    // 20 s hold 21 movements (period 0.9137 s); the last may not come to rest.
    REQUIRE(r.frame_counting_ms.size() >= 20);
    for (double v : r.frame_counting_ms) CHECK(std::abs(v - 37.3) < frame_ms);
    const double mean = std::accumulate(r.frame_counting_ms.begin(), r.frame_counting_ms.end(), 0.0) /
                        static_cast<double>(r.frame_counting_ms.size());
    CHECK(std::abs(mean - 37.3) <= frame_ms / 2);
    REQUIRE(r.shift_ms.size() == r.frame_counting_ms.size());
    for (double v : r.shift_ms) CHECK(std::abs(v - 37.3) <= frame_ms / 2);
  }
}

TEST_CASE("a camera sees a slow panel transition late", "[camera_rig][panel]") {
  // A pixel held (full persistence) from 0 to 10 ms, written at 0 from
  // 0 to 1 degree. An LCD's exponential transition, 10 % to 90 % in
  // r = 4 ms: 1 - exp(-t / tau), tau = r / ln 9. An exposure over
  // [0, e] sees its mean, 1 - (tau / e)(1 - exp(-e / tau)); an OLED's
  // linear one over r sees e / (2r) for e <= r.
  const std::vector<measurement::LitAngle> lit{{Time::zero(), Time::ms(10), 1.0, Time::zero(), 0.0}};
  const double tau = 4.0 / std::log(9.0);
  const measurement::DisplaySignal lcd(lit, {measurement::PanelRise::Curve::exponential, Time::ms(4)});
  for (const double e : {1.0, 2.0, 4.0, 8.0}) {
    CAPTURE(e);
    const double expected = 1.0 - (tau / e) * (1.0 - std::exp(-e / tau));
    CHECK(*lcd.seen(Time::zero(), Time::from_ms(e)) == Approx(expected).margin(2e-3));
  }
  const measurement::DisplaySignal oled(lit, {measurement::PanelRise::Curve::linear, Time::ms(4)});
  CHECK(*oled.seen(Time::zero(), Time::ms(2)) == Approx(0.25).margin(2e-3));
  const measurement::DisplaySignal instant(lit);
  CHECK(*instant.seen(Time::zero(), Time::ms(2)) == Approx(1.0));
  // A threshold of half the change in 1 ms exposures: crossed in the first
  // exposure at once, and only once the transition has passed half way on the
  // LCD: tau ln 2 = 1.26 ms into it, so in the exposure [1, 2] ms.
  auto first_over_half = [](const measurement::DisplaySignal& s) {
    for (int k = 0; k < 10; ++k)
      if (*s.seen(Time::ms(k), Time::ms(k + 1)) > 0.5) return k;
    return -1;
  };
  CHECK(first_over_half(instant) == 0);
  CHECK(first_over_half(lcd) == 1);
}

TEST_CASE("the application's motion flag and its calibration", "[camera_rig]") {
  // Angles 0, 0.02, 0, 0.3, 1.0, 1.0 shown 10 ms apart: changes 0.02, 0.02,
  // 0.3, 0.7, 0. Calibrated over the first 25 ms (changes 0.02 and 0.02):
  // 1.1 x 0.02 = 0.022. Flags: 0, 0, 0, 1, 1, 0; a frame behind: 0, 0, 0, 0, 1, 1.
  std::vector<measurement::LitAngle> lit;
  const double angles[] = {0.0, 0.02, 0.0, 0.3, 1.0, 1.0};
  for (int i = 0; i < 6; ++i) lit.push_back({Time::ms(10 * i), Time::ms(10 * i + 1), angles[i], Time::ms(10 * i), 0.0});
  const double threshold = measurement::calibrated_flag_threshold(lit, Time::ms(25), 1.1);
  CHECK(threshold == Approx(0.022));
  const auto now = measurement::motion_flags(lit, threshold);
  const auto late = measurement::motion_flags(lit, threshold, 1);
  const double expect_now[] = {0, 0, 0, 1, 1, 0}, expect_late[] = {0, 0, 0, 0, 1, 1};
  for (int i = 0; i < 6; ++i) {
    CHECK(now[static_cast<size_t>(i)].angle_deg == expect_now[i]);
    CHECK(late[static_cast<size_t>(i)].angle_deg == expect_late[i]);
    // Each flag's transition starts from the one before.
    if (i > 0) CHECK(late[static_cast<size_t>(i)].from_deg == expect_late[i - 1]);
  }
}
