// SteamVR's and the Oculus runtimes' pacing on the Index profile: the
// running start the application can still make holds the refresh rate; an
// application that cannot is throttled to half rate with every other
// refresh re-projected (docs/pacing.md). Expectations derived below.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "scenario_helpers.hpp"

using latsim::testing::run_shipped;
using Json = nlohmann::json;

namespace {

double value(const Json& f, const std::string& name) {
  const Json& v = f.at(name);
  return v.is_object() ? v.at("mean").get<double>() : v.get<double>();
}

/// index_90hz.json with its game thread taking `cpu_ms`, its render thread
/// nothing and its GPU 1 ms, for 4 s.
Json index_90hz(double cpu_ms, std::vector<std::string> more = {}) {
  std::vector<std::string> o = {"/duration_s=4", "/pipeline/stages/0/cost/fixed_ms=" + std::to_string(cpu_ms),
                                "/pipeline/stages/1/cost/fixed_ms=0", "/pipeline/stages/2/cost/fixed_ms=1"};
  o.insert(o.end(), more.begin(), more.end());
  return run_shipped("devices/index_90hz.json", o);
}

}  // namespace

TEST_CASE("SteamVR: 10 ms of CPU work holds 90 Hz", "[pacing][steamvr]") {
  // T = 11.11 ms. WaitGetPoses returns at W_k = V_k - 3 ms; the game thread
  // works 10 ms and asks again at W_k + 10 ms, before the next running start
  // W_k + T = W_k + 11.11 ms: it makes every one. The render thread takes
  // the frame when the next begins (W_k + T), the GPU's 1 ms follows, and
  // the frame is held for the retrace it was predicted for, V_k + 2T: one
  // new frame every refresh, none late, nothing throttled.
  const Json f = index_90hz(10.0);
  CHECK(value(f, "application_frame_rate_hz") == Approx(90.0).margin(0.5));
  CHECK(value(f, "frames_missed") == 0);
  CHECK(value(f, "frames_synthesised") == 0);
  CHECK(value(f, "throttle_raised") == 0);
}

TEST_CASE("SteamVR: 12 ms of CPU work falls to interleaved reprojection", "[pacing][steamvr]") {
  // With 12 ms the thread asks again at W_k + 12 ms, after W_k + T: the
  // first running start it can make is W_k + 2T. Each such frame slips past
  // the rate it was paced for: a late frame. After `late_frames` (5) late
  // frames among the last 20, the throttle rises to half rate: frames are
  // planned two refreshes apart (W_k + 2T is exactly the next one's running
  // start, so none slips again), each shown at two refreshes, the second
  // re-projected (synthesised, not missed). Nothing brings the level down:
  // a frame is early only if its thread was ready for the running start one
  // refresh sooner (W_k + T), never with 12 ms of work. So the application
  // runs at 45 Hz; the refreshes before the throttle engaged (5 late frames,
  // each followed by one re-projected refresh) are the only misses.
  for (const char* mode : {"interleaved", "motion_smoothing"}) {
    const Json f = index_90hz(12.0, {std::string("/pipeline/pacing/steamvr/reprojection=") + mode});
    CAPTURE(mode);
    CHECK(value(f, "application_frame_rate_hz") == Approx(45.0).margin(0.5));
    CHECK(value(f, "throttle_raised") == 1);
    CHECK(value(f, "frames_missed") <= 6);
    // Every other refresh of the 4 s (360 refreshes) is a synthesised one, less the first frames'.
    CHECK(value(f, "frames_synthesised") == Approx(180.0).margin(8.0));
  }
}

TEST_CASE("SteamVR without reprojection lets a slow application miss every other refresh", "[pacing][steamvr]") {
  // With throttling off the rate is the same (45 Hz: the running start
  // rule) but nothing plans the repeats: every other refresh is a miss.
  const Json f = index_90hz(12.0, {"/pipeline/pacing/steamvr/reprojection=off"});
  CHECK(value(f, "application_frame_rate_hz") == Approx(45.0).margin(0.5));
  CHECK(value(f, "throttle_raised") == 0);
  CHECK(value(f, "frames_synthesised") == 0);
  CHECK(value(f, "frames_missed") == Approx(180.0).margin(8.0));
}

TEST_CASE("SteamVR shows a frame no sooner than the refresh it was predicted for", "[pacing][steamvr]") {
  // The light profile workload, but the render thread and GPU all but free:
  // the frame is done 0.4 ms after its handover at W_k + T, before retrace
  // V_k + T, yet held to V_k + 2T, the refresh its poses were predicted for:
  // its pose is read at W_k = V_k - 3 ms, so the head's motion-to-photon is
  // 3 ms + 2T + T (the global flash waits for the whole panel) + 1 ms
  // (the LCD's response) + 0.24 ms (half the flash) + the sample's age
  // (readings at 1 kHz over a 1 kHz poll: 0.5 + 0.5 ms on average).
  const Json f = run_shipped("devices/index_90hz.json", {"/duration_s=4", "/pipeline/stages/1/cost/fixed_ms=0",
                                                         "/pipeline/stages/2/cost/fixed_ms=0.1"});
  const double t = 1000.0 / 90.0;
  CHECK(value(f, "motion_to_photon_ms") == Approx(3.0 + 3.0 * t + 1.0 + 0.24 + 1.0).margin(0.6));
  CHECK(value(f, "frames_missed") == 0);
}

namespace {

/// index_90hz.json for 4 s with VRChat's render thread (1.5 ms, a frame
/// behind) and GPU (3 ms), its game thread taking `late_ms` in the frames
/// `late(j)` picks and 10 ms in the others (cost_shape steps, one per frame).
Json index_90hz_pattern(bool (*late)(int), double late_ms = 12.0) {
  Json steps = Json::array();
  for (int j = 0; j < 400; ++j) steps.push_back(Json::array({j, late(j) ? late_ms : 10.0}));
  const Json shape = {{"steps", steps}};
  std::string shape_set = "/pipeline/stages/0/cost_shape=";
  shape_set.append(shape.dump());
  return run_shipped("devices/index_90hz.json",
                     {"/duration_s=4", "/pipeline/stages/0/cost/fixed_ms=10", "/pipeline/stages/1/cost/fixed_ms=1.5",
                      "/pipeline/stages/2/cost/fixed_ms=3", shape_set});
}

}  // namespace

TEST_CASE("SteamVR lowers the throttle after 30 frames that would have made full rate", "[pacing][steamvr]") {
  // Frames 0-9 take 12 ms, the rest 10 ms (T = 11.11 ms). Frame k is judged
  // when its thread asks for frame k + 1. Frames 0-4 slip past their running
  // start (late); at the fifth, judged as frame 5 is planned, the level rises,
  // so frames 5 on are planned at half rate. Frames 5-9 (12 ms) fit two
  // refreshes (not late) but not one (not early). Frames 10 on are ready a
  // refresh sooner (10 ms <= T), and their GPU would have been done in time
  // at full rate: the render thread takes a frame when the next begins, a
  // refresh sooner at full rate, so the GPU is done at W + T + 1.5 + 0.3 + 3
  // ms, before that rate's latch W + 3 ms + 2T less the compositor's 0.5 ms.
  // Thirty of them (frames 10-39) lower the level as frame 40 is planned:
  // 35 frames throttled (5-39), raised once. The refreshes: frames 0-4 two
  // each, 5-39 two each, then one each: 80 refreshes for 40 frames and 280
  // frames in the other 280 of the 360, so 320 frames in 4 s (80 Hz).
  const Json f = index_90hz_pattern([](int j) { return j < 10; });
  CHECK(value(f, "throttle_raised") == 1);
  CHECK(value(f, "throttled_frames") == 35);
  CHECK(value(f, "application_frame_rate_hz") == Approx(80.0).margin(1.0));
}

TEST_CASE("SteamVR throttles a frame late in four and keeps it there", "[pacing][steamvr]") {
  // Frames 3, 7, 11, ... take 12 ms. At full rate each of them is late: the
  // fifth (frame 19) is judged as frame 20 is planned, and 5 of the last 20
  // raise the level. Frames 0-19 took 15 refreshes plus 2 for each of the 5
  // late ones: 25. At half rate no frame is late, but a 12 ms frame in every
  // four ends each run of frames that would have made full rate at 3: the
  // level never falls. The other 335 refreshes of the 4 s hold 167 frames,
  // all throttled, at two refreshes each.
  const Json f = index_90hz_pattern([](int j) { return j % 4 == 3; });
  CHECK(value(f, "throttle_raised") == 1);
  CHECK(value(f, "throttled_frames") == Approx(167.0).margin(1.0));
}

TEST_CASE("SteamVR leaves a frame late in eight at full rate", "[pacing][steamvr]") {
  // Frames 7, 15, 23, ... take 12 ms: any 20 frames hold at most 3 of them,
  // under the 5 that raise the level. Each costs one refresh more (the next
  // running start it can make is two refreshes on): 8 frames in 9
  // refreshes, 80 Hz, nothing throttled.
  const Json f = index_90hz_pattern([](int j) { return j % 8 == 7; });
  CHECK(value(f, "throttle_raised") == 0);
  CHECK(value(f, "throttled_frames") == 0);
  CHECK(value(f, "application_frame_rate_hz") == Approx(80.0).margin(1.0));
}
