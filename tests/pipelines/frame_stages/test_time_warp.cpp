// Asynchronous time warp under overload, half-rate synthesis, synchronous
// warp, rotation against positional warp, and a compositor sharing a
// preemptible GPU; every expectation is derived in the comment above it.
#include <catch2/catch.hpp>

#include "rig.hpp"

using latsim::testing::Rig;
using latsim::testing::RigOptions;
using latsim::testing::stage;
using latsim::testing::walking;
using namespace latsim::pipelines::frame_stages;

namespace {

constexpr auto kRetrace = StartRule::retrace;
constexpr auto kLate = StartRule::late;

/// The application of the overload cases on the reference display (16 ms):
/// I (1 ms, at a retrace, reads the pose) on the CPU, then G on the GPU,
/// two frames in flight; a warp W of 1 ms on its own processor, late, just
/// before each retrace.
FrameStagesSpec overloaded(double gpu_ms, WarpSpec::Mode mode) {
  FrameStagesSpec s;
  s.processors = {ProcessorSpec{"cpu", {}}, ProcessorSpec{"gpu", {}}, ProcessorSpec{"warp", {}}};
  s.max_frames_in_flight = 2;
  s.stages = {stage("I", {0}, 1, kRetrace, true), stage("G", {1}, gpu_ms)};
  WarpSpec w;
  w.mode = mode;
  w.stages = {stage("W", {2}, 1, kLate, true)};
  s.warp = w;
  return s;
}

double position_mean(const nlohmann::json& figures, int rewarps) {
  for (const auto& b : figures["residual_by_rewarps"])
    if (b["rewarps"].get<int>() == rewarps) return b["position_mm_mean"].get<double>();
  return -1.0;
}

}  // namespace

TEST_CASE("time warp: an application needing 1.5 refreshes misses one in three, every refresh is still warped") {
  // G takes 24 ms = 1.5 refreshes. Frames are admitted two in flight and start
  // at retraces: frame samples at 0, 16, 32, 64, 80, 112, 128, ... (two a
  // refresh apart, then a gap), completions every 24 ms at 25, 49, 73, 97 ...
  // The warp at V - 1 finds, per 48 ms (three refreshes): two new frames and
  // one already shown, so a third of the refreshes re-warp: 2 s = 125
  // refreshes; the first has no image yet (frame 0 completes at 25), so 124
  // warps (retraces 1 to 125: the warp for the retrace at exactly 2 s ends at
  // the end instant and counts), of which retraces 3, 6, ..., 123 re-warp
  // (the hour-long case below derives which): 41.
  RigOptions o;
  o.motion = walking(1.0);
  Rig rig(overloaded(24.0, WarpSpec::Mode::rotation), o);
  rig.run(2.0);
  const auto& f = rig.figures;
  CHECK(f["refreshes_without_image"].get<int64_t>() == 1);
  CHECK(f["warps"].get<int64_t>() == 124);
  CHECK(f["warps_late"].get<int64_t>() == 0);
  CHECK(f["frames_missed"].get<int64_t>() == 41);
  CHECK(f["frames_rewarped"].get<int64_t>() == 41);
  CHECK(f["application_frame_rate_hz"].get<double>() == Approx(1000.0 / 24.0).margin(1.0));
  // Rotation only: the orientation is read at V - 1 (1 to 16.9 ms before the
  // lines are lit), the position is the frame's, 48 ms old at the retrace when
  // new (64 ms when re-warped), plus 0 to 15.9 ms down the screen.
  CHECK(rig.stat("rotation_latency_ms", "min") == Approx(1.0).margin(1e-6));
  CHECK(rig.stat("rotation_latency_ms", "max") == Approx(16.9).margin(1e-6));
  CHECK(rig.stat("translation_latency_ms", "max") == Approx(64.0 + 15.9).margin(1e-6));
  CHECK(rig.mtp("max") == Approx(64.0 + 15.9).margin(1e-6));
  // Walking at 1 m/s the position error is 1 mm per ms of that age: on
  // average over the lines 48 + 7.95 mm when new, 64 + 7.95 mm re-warped
  // (frame 0, shown 32 ms and 48 ms old at start-up, pulls each down a little).
  CHECK(position_mean(f, 0) == Approx(55.95).margin(1.0));
  CHECK(position_mean(f, 1) == Approx(71.95).margin(1.0));
  CHECK(position_mean(f, 1) - position_mean(f, 0) == Approx(16.0).margin(1.0));
  CHECK(rig.stat("residual_orientation_error_deg", "max") < 1e-9);  // a straight walk does not turn
}

TEST_CASE("time warp: warping with depth takes the position from the warp's pose too") {
  // The same overload, positional: the whole pose is read at V - 1, so
  // motion-to-photon is 1 to 16.9 ms and the position error 1 mm per ms of
  // it: 8.95 mm on average, new or re-warped alike.
  RigOptions o;
  o.motion = walking(1.0);
  Rig rig(overloaded(24.0, WarpSpec::Mode::positional), o);
  rig.run(2.0);
  CHECK(rig.mtp("min") == Approx(1.0).margin(1e-6));
  CHECK(rig.mtp("max") == Approx(16.9).margin(1e-6));
  CHECK(position_mean(rig.figures, 0) == Approx(8.95).margin(1e-3));
  CHECK(position_mean(rig.figures, 1) == Approx(8.95).margin(1e-3));
  // One pose: rotation latency is the whole pose's (docs/figures.md).
  CHECK(rig.stat("rotation_latency_ms", "mean") == Approx(rig.mtp("mean")).margin(1e-9));
}

TEST_CASE("time warp: half rate throttles the application and synthesises every other refresh") {
  // G of 20 ms does not fit a refresh but fits two: with half rate the
  // application starts frames at even retraces only, each frame is warped
  // twice (new, then synthesised) and none is missed.
  FrameStagesSpec s = overloaded(20.0, WarpSpec::Mode::rotation);
  s.warp->half_rate = true;
  Rig rig(s);
  rig.run(2.0);
  const auto& f = rig.figures;
  CHECK(f["frames_missed"].get<int64_t>() == 0);
  CHECK(f["application_frame_rate_hz"].get<double>() == Approx(31.25).margin(1.0));
  // Warps aim at retraces 1 to 125 (the one at 2 s is met at the end instant
  // and counts, as in the overload case); at retrace 1 frame 0 (0 to 21 ms)
  // is not done: 124 warps, for retraces 2 to 125 in pairs (new, synthesised),
  // frame k starting at retrace 2k: 62 synthesised.
  CHECK(f["warps"].get<int64_t>() == 124);
  CHECK(f["frames_synthesised"].get<int64_t>() == 62);
}

TEST_CASE("time warp: a synchronous warp leaves the display showing the last image when the application misses") {
  // As the overload case, but the warp runs only for new frames: the
  // refreshes that would re-warp there (3, 6, ..., 123: 41 of them) repeat the
  // previous warped image unwarped, and the other 124 - 41 = 83 are warped.
  FrameStagesSpec s = overloaded(24.0, WarpSpec::Mode::rotation);
  s.warp->asynchronous = false;
  Rig rig(s);
  rig.run(2.0);
  const auto& f = rig.figures;
  CHECK(f["frames_rewarped"].get<int64_t>() == 0);
  CHECK(f["frames_missed"].get<int64_t>() == 41);
  CHECK(f["warps"].get<int64_t>() == 83);
}

TEST_CASE("time warp: a compositor sharing a preemptible GPU learns the wait and meets every retrace") {
  // The warp runs on the application's GPU, which switches only at 0.5 ms
  // slice ends: the warp may wait up to 0.5 ms, which late scheduling
  // measures and allows for from then on (the first warps may be late).
  FrameStagesSpec s = overloaded(24.0, WarpSpec::Mode::rotation);
  s.processors[1].preemption_slice = latsim::des::Time::us(500);
  s.warp->stages[0].processors = {1};
  Rig rig(s);
  rig.run(2.0);
  const auto& f = rig.figures;
  CHECK(f["warps_late"].get<int64_t>() <= 2);
  CHECK(f["warps"].get<int64_t>() >= 122);
  // The orientation is never older than the warp's 1 ms plus the 0.5 ms it
  // may wait plus a sample period, plus the scanout.
  CHECK(rig.stat("rotation_latency_ms", "max") <= 1.0 + 0.5 + 1.0 + 15.9 + 1e-6);
}

TEST_CASE("time warp: an hour of overload re-warps exactly one refresh in three") {
  // The overload case for an hour (225,000 refreshes of 16 ms) on two lines
  // (the bottom one lit 8 ms after the top). The GPU, busy from frame 0 on,
  // completes a frame every 24 ms, at 25 + 24k ms. The warp for retrace m
  // (at 16m) reads at 16m - 1 and finds a new frame if one completed in
  // (16m - 17, 16m - 1]: 25 falls in m = 2, 49 in m = 4, 73 in m = 5, 97 in
  // m = 7, 121 in m = 8, ... (never on a boundary: 25 + 24k = 16m - 1 has no
  // integer solution), so every retrace m = 3, 6, 9, ... re-warps and m = 1
  // has no image yet. Retraces 1 to 225,000 are aimed at (the last ends at
  // the end instant and counts): 224,999 warps, 75,000 re-warps, none late.
  // Frame k > 0 is sampled at a retrace and shown 48 ms later, re-warped
  // 64 ms later; frame 0 (sampled at 0, complete at 25) is shown at 32 ms:
  // translation latency 32 to 64 + 8 ms, the orientation 1 to 1 + 8 ms old.
  RigOptions o;
  o.lines = 2;
  Rig rig(overloaded(24.0, WarpSpec::Mode::rotation), o);
  rig.run(3600.0);
  const auto& f = rig.figures;
  CHECK(f["refreshes_without_image"].get<int64_t>() == 1);
  CHECK(f["warps"].get<int64_t>() == 224999);
  CHECK(f["warps_late"].get<int64_t>() == 0);
  CHECK(f["frames_missed"].get<int64_t>() == 75000);
  CHECK(f["frames_rewarped"].get<int64_t>() == 75000);
  CHECK(rig.stat("rotation_latency_ms", "min") == Approx(1.0).margin(1e-6));
  CHECK(rig.stat("rotation_latency_ms", "max") == Approx(9.0).margin(1e-6));
  CHECK(rig.stat("translation_latency_ms", "min") == Approx(32.0).margin(1e-6));
  CHECK(rig.stat("translation_latency_ms", "max") == Approx(72.0).margin(1e-6));
}
