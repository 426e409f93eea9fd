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
