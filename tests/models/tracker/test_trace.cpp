// Trace files: both formats, repairs (repeats, sign flips), errors, replay.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <glm/geometric.hpp>

#include "latsim/tracker/motion_source.hpp"
#include "latsim/tracker/trace.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using namespace latsim::tracker;
using latsim::des::Time;

namespace {

// A uniquely named file in the temporary directory, removed afterwards.
class TempFile {
 public:
  TempFile(const std::string& name, const std::string& contents)
      : path_(std::filesystem::temp_directory_path() /
              ("latsim-trace-" + std::to_string(::getpid()) + "-" + name)) {
    std::ofstream(path_) << contents;
  }
  ~TempFile() { std::filesystem::remove(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

std::string error_of(const std::filesystem::path& file) {
  try {
    (void)load_trace(file);
  } catch (const TraceError& e) {
    return e.what();
  }
  return "no error";
}

const std::filesystem::path kRealTrace = std::filesystem::path(LATSIM_SOURCE_DIR) / "scenarios/data/user1_quaternion.txt";

}  // namespace

TEST_CASE("latsim CSV traces load with positions and normalised quaternions", "[trace]") {
  const TempFile f("csv.csv",
                   "t_s,px,py,pz,qw,qx,qy,qz\n"
                   "0.0, 0, 1.7, 0, 2, 0, 0, 0\n"
                   "0.5, 1, 1.7, 0, 1, 0, 0, 0\n"
                   "\n"
                   "# a comment\n"
                   "1.25,2,1.7,-1,0.9238795325112867,0,0.3826834323650898,0\n");
  const Trace t = load_trace(f.path());
  REQUIRE(t.samples.size() == 3);
  CHECK(t.has_position);
  CHECK(t.samples[0].pose.orientation == glm::dquat{1, 0, 0, 0});
  CHECK(t.samples[2].t == Time::ms(1250));
  CHECK(t.samples[2].pose.position_m == glm::dvec3{2.0, 1.7, -1.0});
  CHECK(yaw_of(t.samples[2].pose.orientation) == Approx(units::kPi / 4.0).epsilon(1e-12));
}

TEST_CASE("quaternions whose squares overflow still normalise to unit length", "[trace]") {
  // (w, x, y, z) = (1, 0, 1e300, 0): the squared norm overflows a double, but
  // the direction is y to within 1e-300, so the unit quaternion is (0, 0, 1, 0);
  // 3e300 and 4e300 on w and z give (0.6, 0, 0, 0.8).
  const TempFile f("huge.csv",
                   "t_s,px,py,pz,qw,qx,qy,qz\n"
                   "0.0, 0, 0, 0, 1, 0, 1e300, 0\n"
                   "0.5, 0, 0, 0, 3e300, 0, 0, 4e300\n");
  const Trace t = load_trace(f.path());
  REQUIRE(t.samples.size() == 2);
  CHECK(t.samples[0].pose.orientation.y == 1.0);
  CHECK(t.samples[0].pose.orientation.w == Approx(0.0).margin(1e-12));
  CHECK(t.samples[1].pose.orientation.w == Approx(0.6).epsilon(1e-15));
  CHECK(t.samples[1].pose.orientation.z == Approx(0.8).epsilon(1e-15));
}

TEST_CASE("repeated timestamps keep the later row and sign flips are removed", "[trace]") {
  const TempFile f("repeat.csv",
                   "t_s,px,py,pz,qw,qx,qy,qz\n"
                   "0.0,0,0,0,1,0,0,0\n"
                   "0.1,0,0,0,1,0,0,0\n"
                   "0.1,5,0,0,0.9950041652780258,0,0.09983341664682815,0\n"
                   "0.2,0,0,0,-0.9800665778412416,0,-0.19866933079506122,0\n");
  const Trace t = load_trace(f.path());
  REQUIRE(t.samples.size() == 3);
  CHECK(t.repeated_timestamps_dropped == 1);
  CHECK(t.samples[1].pose.position_m.x == 5.0);
  CHECK(t.sign_flips_removed == 1);
  CHECK(t.samples[2].pose.orientation.w > 0.0);
}

TEST_CASE("Corbillon traces convert from Unity's left-handed frame", "[trace]") {
  // Unity: q rotates +z (forward) by 30 degrees about y, towards +x (the right).
  const double h = units::deg_to_rad(15.0);
  const std::string row = std::to_string(std::cos(h)) + " 0 " + std::to_string(std::sin(h)) + " 0";
  const TempFile f("unity.txt", "timestamp viewpoint w x y z\n0.0 0 " + row + "\n0.016 1 0.5 0.5 -0.5 0.5\n");
  const Trace t = load_trace(f.path());
  REQUIRE(t.samples.size() == 2);
  CHECK_FALSE(t.has_position);
  // In latsim the head turned right: forward is (sin 30, 0, -cos 30), yaw -30 degrees.
  const glm::dvec3 fwd = forward_of(t.samples[0].pose.orientation);
  CHECK(fwd.x == Approx(0.5).epsilon(1e-5));
  CHECK(fwd.z == Approx(-std::sqrt(0.75)).epsilon(1e-5));

  // In general the converted rotation is M R M with M mirroring z.
  const glm::dquat unity{0.5, 0.5, -0.5, 0.5};
  const glm::dvec3 v{0.3, -0.7, 0.2};
  const glm::dvec3 mirrored_v{v.x, v.y, -v.z};
  const glm::dvec3 unity_result = unity * mirrored_v;
  const glm::dvec3 expected{unity_result.x, unity_result.y, -unity_result.z};
  const glm::dvec3 got = t.samples[1].pose.orientation * v;
  CHECK(glm::length(got - expected) < 1e-12);
}

TEST_CASE("malformed rows name the file and line", "[trace]") {
  const std::string header = "t_s,px,py,pz,qw,qx,qy,qz\n";
  const std::string good = "0.0,0,0,0,1,0,0,0\n";
  struct Case {
    std::string name;
    std::string contents;
    std::string reason;
  };
  const Case cases[] = {
      {"columns.csv", header + good + "0.1,0,0,0,1,0,0\n", ":3: expected 8 columns, found 7"},
      {"text.csv", header + good + "0.1,0,zero,0,1,0,0,0\n", ":3: column py is not a number: 'zero'"},
      {"nan.csv", header + good + "0.1,0,0,0,nan,0,0,0\n", ":3: column qw is not finite: 'nan'"},
      {"inf.txt", "timestamp viewpoint w x y z\n0.0 0 1 0 0 0\n\n0.2 0 1 inf 0 0\n", ":4: column x is not finite: 'inf'"},
      {"zero.csv", header + good + "0.1,0,0,0,0,0,0,0\n", ":3: zero quaternion (it describes no orientation)"},
      {"header.csv", "time,x,y\n" + good, ":1: unrecognised header"},
      {"empty.csv", header, ":1: trace has a header but no data rows"},
  };
  for (const Case& c : cases) {
    const TempFile f(c.name, c.contents);
    const std::string expected = f.path().string() + c.reason;
    INFO(c.name);
    CHECK(error_of(f.path()).substr(0, expected.size()) == expected);
  }
}

TEST_CASE("decreasing timestamps are rejected", "[trace]") {
  const TempFile f("decreasing.txt", "timestamp viewpoint w x y z\n0.0 0 1 0 0 0\n0.5 0 1 0 0 0\n0.4 0 1 0 0 0\n");
  const std::string message = error_of(f.path());
  const std::string prefix = f.path().string() + ":4: timestamp ";
  CHECK(message.substr(0, prefix.size()) == prefix);
  CHECK(message.find("must not decrease") != std::string::npos);
  CHECK_THROWS_AS(load_trace("/nonexistent/latsim-trace.csv"), TraceError);
}

TEST_CASE("the real head trace loads and replays smoothly", "[trace]") {
  const auto trace = std::make_shared<const Trace>(load_trace(kRealTrace));
  CHECK(trace->samples.size() == 16053);
  CHECK(trace->repeated_timestamps_dropped == 0);
  CHECK(trace->sign_flips_removed > 100);  // the recording flips sign hundreds of times
  CHECK(trace->end().to_seconds() == Approx(272.056).epsilon(1e-5));
  for (size_t i = 1; i < trace->samples.size(); ++i) {
    REQUIRE(trace->samples[i].t > trace->samples[i - 1].t);
    REQUIRE(glm::dot(trace->samples[i].pose.orientation, trace->samples[i - 1].pose.orientation) >= 0.0);
  }

  const TraceMotion motion(trace, Time::zero(), false);
  // Midway between neighbours the replay is half the way round the short
  // arc; a long-arc slip across a sign flip would land near pi instead.
  int64_t checked = 0;
  for (size_t i = 0; i + 1 < trace->samples.size(); ++i) {
    const TraceSample& a = trace->samples[i];
    const TraceSample& b = trace->samples[i + 1];
    const Time mid = a.t + Time::ps((b.t - a.t).ticks() / 2);
    const double f = static_cast<double>((mid - a.t).ticks()) / static_cast<double>((b.t - a.t).ticks());
    const glm::dquat q = motion.pose_at(mid).orientation;
    REQUIRE(std::abs(glm::length(q) - 1.0) < 1e-12);
    REQUIRE(angle_between(a.pose.orientation, q) ==
            Approx(f * angle_between(a.pose.orientation, b.pose.orientation)).margin(1e-9));
    ++checked;
  }
  CHECK(checked == 16052);
  // Sample times reproduce the samples.
  const TraceSample& s = trace->samples[5000];
  CHECK(angle_between(motion.pose_at(s.t).orientation, s.pose.orientation) < 1e-12);
  // Unit norm at every millisecond of the first minute.
  for (int64_t ms = 0; ms < 60000; ++ms)
    REQUIRE(std::abs(glm::length(motion.pose_at(Time::ms(ms)).orientation) - 1.0) < 1e-12);
}

TEST_CASE("trace replay offsets, clamps and loops", "[trace]") {
  const TempFile f("loop.csv",
                   "t_s,px,py,pz,qw,qx,qy,qz\n"
                   "1.0,0,0,0,1,0,0,0\n"
                   "2.0,2,0,0,1,0,0,0\n"
                   "3.0,4,0,0,1,0,0,0\n");
  const auto trace = std::make_shared<const Trace>(load_trace(f.path()));
  const TraceMotion clamped(trace, Time::s(1), false);
  CHECK(clamped.pose_at(Time::ms(500)).position_m.x == Approx(1.0));  // trace time 1.5 s
  CHECK(clamped.pose_at(Time::s(10)).position_m.x == 4.0);
  CHECK(TraceMotion(trace, Time::zero(), false).pose_at(Time::zero()).position_m.x == 0.0);
  // Looping: a lap is 2 s of recording plus one mean interval (1 s) of return.
  const TraceMotion looping(trace, Time::s(1), true);
  CHECK(looping.pose_at(Time::ms(2500)).position_m.x == Approx(2.0));  // halfway back from 4 to 0
  CHECK(looping.pose_at(Time::ms(3500)).position_m.x == Approx(1.0));  // next lap, 1.5 s
  CHECK(looping.pose_at(Time::ms(-1500)).position_m.x == Approx(3.0));  // previous lap, 2.5 s
}
