// Building tracker models from scenario objects through their parameter declarations.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>

#include "latsim/sections/shared.hpp"
#include "latsim/tracker/motion_and_transport.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using namespace latsim::tracker;
using latsim::des::Time;
using latsim::scenario::ScenarioDocument;
using latsim::scenario::ScenarioError;
using latsim::scenario::Section;
using nlohmann::json;

namespace {

ScenarioDocument doc(json j) {
  return ScenarioDocument::from_json(std::move(j), std::filesystem::path(LATSIM_SOURCE_DIR) / "scenarios");
}

std::string pointer_of_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const ScenarioError& e) {
    return e.pointer();
  }
  return "no error";
}

/// Reads the object `key` of the document's root through its declaration.
template <class T>
T read(const ScenarioDocument& d, const char* key) {
  T p{};
  Section s(d.root().child(key));
  latsim::sections::bind(s, p);
  return p;
}

std::unique_ptr<MotionSource> make_motion_at(const ScenarioDocument& d, const char* key) {
  return make_motion(read<MotionParams>(d, key));
}
TrackerParams parse_tracker_at(const ScenarioDocument& d, const char* key) { return read<TrackerParams>(d, key); }
std::unique_ptr<Transport> make_transport_at(const ScenarioDocument& d, const char* key) {
  return make_transport(read<TransportParams>(d, key));
}

}  // namespace

TEST_CASE("motion sources are built from scenario objects", "[config]") {
  const auto d = doc(json::parse(R"({
    "still": {"position_m": [0, 1.7, 0]},
    "spin": {"type": "constant", "rate_deg_s": 45},
    "wave": {"type": "sinusoid", "yaw_amplitude_deg": 20, "yaw_frequency_hz": 1},
    "walk": {"type": "walk", "points": [[0, 1.7, 0], [4, 1.7, 0]], "speed_m_s": 2},
    "trace": {"type": "trace", "file": "data/user1_quaternion.txt", "loop": false},
    "bad_axis": {"type": "constant", "axis": [0, 0, 0]},
    "bad_walk": {"type": "walk", "points": [[0, 1]]},
    "bad_file": {"type": "trace", "file": "data/no-such-trace.txt"}
  })"));
  const auto still = make_motion_at(d, "still");
  CHECK(still->is_still());
  CHECK(still->pose_at(Time::s(3)).position_m.y == 1.7);
  const auto spin = make_motion_at(d, "spin");
  CHECK(spin->name() == "constant");
  CHECK(yaw_of(spin->pose_at(Time::s(1)).orientation) == Approx(units::kPi / 4.0).epsilon(1e-12));
  const auto wave = make_motion_at(d, "wave");
  CHECK(yaw_of(wave->pose_at(Time::ms(250)).orientation) == Approx(units::deg_to_rad(20.0)).epsilon(1e-12));
  CHECK(make_motion_at(d, "walk")->pose_at(Time::s(1)).position_m.x == Approx(2.0));
  const auto trace = make_motion_at(d, "trace");
  CHECK(trace->name() == "trace");
  CHECK(pointer_of_error([&] { (void)make_motion_at(d, "bad_axis"); }) == "/bad_axis/axis");
  // The row with two numbers instead of three.
  CHECK(pointer_of_error([&] { (void)make_motion_at(d, "bad_walk"); }) == "/bad_walk/points/0");
  CHECK(pointer_of_error([&] { (void)make_motion_at(d, "bad_file"); }) == "/bad_file/file");
}

TEST_CASE("tracker parameters parse with exact rates and noise", "[config]") {
  const auto d = doc(json::parse(R"({
    "plain": {},
    "ntsc": {"rate_hz": "60000/1001", "internal_delay_ms": 5, "jitter_ms": 0.5, "jitter": "normal",
             "phase_ms": 2, "noise": {"position_stddev_m": 0.001, "orientation_stddev_deg": 0.1}},
    "cov": {"noise": {"covariance": [[1e-6,0,0,0,0,0],[0,1e-6,0,0,0,0],[0,0,1e-6,0,0,0],
                                     [0,0,0,1e-6,0,0],[0,0,0,0,1e-6,0],[0,0,0,0,0,1e-6]]}},
    "not_psd": {"noise": {"covariance": [[1,2,0,0,0,0],[2,1,0,0,0,0],[0,0,1,0,0,0],
                                         [0,0,0,1,0,0],[0,0,0,0,1,0],[0,0,0,0,0,1]]}},
    "negative_rate": {"rate_hz": -30},
    "negative_delay": {"internal_delay_ms": -1}
  })"));
  const TrackerParams plain = parse_tracker_at(d, "plain");
  CHECK(plain.period.num == 1);
  CHECK(plain.period.den == 60);
  CHECK_FALSE(plain.noise_enabled);
  const TrackerParams ntsc = parse_tracker_at(d, "ntsc");
  CHECK(ntsc.period.num == 1001);
  CHECK(ntsc.period.den == 60000);
  CHECK(ntsc.internal_delay == Time::ms(5));
  CHECK(ntsc.jitter == Time::us(500));
  CHECK(ntsc.jitter_shape == TrackerParams::Normal);
  CHECK(ntsc.clock.phase == Time::ms(2));
  CHECK_FALSE(plain.clock.phase.has_value());  // drawn per replication by a run
  CHECK(ntsc.noise_enabled);
  CHECK(ntsc.noise_covariance(0, 0) == Approx(1e-6));
  CHECK(ntsc.noise_covariance(4, 4) == Approx(std::pow(units::deg_to_rad(0.1), 2)));
  CHECK(parse_tracker_at(d, "cov").noise_covariance(5, 5) == 1e-6);
  CHECK(pointer_of_error([&] { (void)parse_tracker_at(d, "not_psd"); }) == "/not_psd/noise/covariance");
  CHECK(pointer_of_error([&] { (void)parse_tracker_at(d, "negative_rate"); }) == "/negative_rate/rate_hz");
  CHECK(pointer_of_error([&] { (void)parse_tracker_at(d, "negative_delay"); }) ==
        "/negative_delay/internal_delay_ms");
}

TEST_CASE("transports parse with defaults and reject bad values", "[config]") {
  const auto d = doc(json::parse(R"({
    "none": {},
    "poll": {"type": "serial", "poll_phase_ms": 4},
    "irq": {"type": "serial", "host": "interrupt", "baud": 9600, "record_bytes": 16, "per_char_interrupt_us": 50},
    "zero_poll": {"type": "serial", "poll_interval_ms": 0},
    "zero_baud": {"type": "serial", "baud": 0},
    "bad_host": {"type": "serial", "host": "dma"}
  })"));
  CHECK(make_transport_at(d, "none")->name() == "direct");
  auto poll = make_transport_at(d, "poll");
  CHECK(poll->name() == "serial");
  CHECK(poll->deliver(Time::zero()) == Time::ms(34));  // 16.7 ms on the line, polls at 4 + 30k ms
  auto irq = make_transport_at(d, "irq");
  const Time expected = Time::from_seconds(160.0 / 9600.0) + Time::us(50);
  CHECK(std::abs((irq->deliver(Time::zero()) - expected).ticks()) <= 1);
  CHECK(pointer_of_error([&] { (void)make_transport_at(d, "zero_poll"); }) == "/zero_poll/poll_interval_ms");
  CHECK(pointer_of_error([&] { (void)make_transport_at(d, "zero_baud"); }) == "/zero_baud/baud");
  CHECK(pointer_of_error([&] { (void)make_transport_at(d, "bad_host"); }) == "/bad_host/host");
}
