// The eleven configurations of "Latency mitigation strategies" (Carmack,
// 2013) built as stage specs and run on the reference display: 62.5 Hz
// (16 ms), no blanking, 160 lines of 0.1 ms; a 1000 Hz tracker with sample 0
// at t = 0 and no delay (500 Hz for continuous time warp). Stage durations
// are read off the article's diagrams, one character per millisecond.
//
// Expected ranges come from the diagrams by hand (docs/modern.md walks
// through each): the pose is read at the start of the sampling stage, the
// top line is lit at the retrace that starts the frame's scanout, the bottom
// line 15.9 ms later. With samples on whole milliseconds and every sampling
// stage starting on a whole millisecond, the sample read is 0 ms old, so the
// simulated min and max must equal the derived values exactly; continuous
// time warp reads at odd milliseconds from a 500 Hz tracker sampling on even
// ones: every read is 1 ms old.
#include <catch2/catch.hpp>

#include "rig.hpp"

using latsim::testing::Rig;
using latsim::testing::stage;
using latsim::testing::streaming;
using namespace latsim::pipelines::frame_stages;

namespace {

constexpr double kLastLine = 15.9;  // the bottom line is lit 159 lines of 0.1 ms after the retrace

FrameStagesSpec base(std::vector<const char*> processors, int in_flight) {
  FrameStagesSpec s;
  for (const char* p : processors) s.processors.push_back(ProcessorSpec{p, {}});
  s.max_frames_in_flight = in_flight;
  return s;
}

/// Runs 1 s and checks the range, and that every refresh got a new frame:
/// 62.5 frames per second (the first ones complete only after 1 to 3 frame
/// times), none missed once the first was shown.
void check_range(FrameStagesSpec spec, double min_ms, double max_ms, int tracker_hz = 1000) {
  latsim::testing::RigOptions o;
  o.tracker_hz = tracker_hz;
  Rig rig(std::move(spec), o);
  rig.run(1.0);
  CHECK(rig.mtp("min") == Approx(min_ms).margin(1e-6));
  CHECK(rig.mtp("max") == Approx(max_ms).margin(1e-6));
  CHECK(rig.figures["frames_missed"].get<int64_t>() == 0);
  CHECK(rig.figures["application_frame_rate_hz"].get<double>() == Approx(62.5).margin(3.0));
}

constexpr int kCpu1 = 0, kCpu2 = 1, kGpu = 2;
constexpr auto kRetrace = StartRule::retrace;
constexpr auto kLate = StartRule::late;

}  // namespace

TEST_CASE("reference: ample performance with vsync shows the pose read at a retrace from the next one") {
  // ISRG------------|VVVVVVVVVVVVVVVV| : read at V_k, G ends at V_k + 4, shown from V_{k+1}: 16 - 32 ms.
  FrameStagesSpec s = base({"cpu", "gpu"}, 2);
  s.stages = {stage("I", {0}, 1, kRetrace, true), stage("S", {0}, 1), stage("R", {0}, 1), stage("G", {1}, 1)};
  check_range(s, 16.0, 16.0 + kLastLine);
}

TEST_CASE("reference: unsynchronized frames replace the front buffer as they complete") {
  // ISRG then VVVV: no overlap (one frame in flight), a frame every 4 ms; the
  // line lit at t shows the frame completed last, read 4 to 8 ms before t.
  FrameStagesSpec s = base({"cpu", "gpu"}, 1);
  s.vsync = false;
  s.stages = {stage("I", {0}, 1, StartRule::after, true), stage("S", {0}, 1), stage("R", {0}, 1), stage("G", {1}, 1)};
  Rig rig(s);
  rig.run(1.0);
  CHECK(rig.mtp("min") == Approx(4.0).margin(1e-6));
  CHECK(rig.mtp("max") == Approx(7.9).margin(1e-6));
  CHECK(rig.figures["application_frame_rate_hz"].get<double>() == Approx(250.0).margin(1.0));
}

TEST_CASE("reference: a CPU and a GPU pipelined a frame apart") {
  // CPU:ISSSSSRRRRRR----|  GPU: |GGGGGGGGGGG----|  : G waits for the swap at V_{k+1}
  // that frees a buffer, shown from V_{k+2}: 32 - 48 ms.
  FrameStagesSpec s = base({"cpu", "gpu"}, 2);
  s.stages = {stage("I", {0}, 1, kRetrace, true), stage("S", {0}, 5), stage("R", {0}, 6), stage("G", {1}, 11)};
  check_range(s, 32.0, 32.0 + kLastLine);
}

TEST_CASE("reference: simulation and rendering on two threads, each a frame apart") {
  // CPU1:ISSSSSSSS  CPU2: |RRRRRRRRR  GPU: | |GGGGGGGGGG : 48 - 64 ms.
  FrameStagesSpec s = base({"cpu1", "cpu2", "gpu"}, 3);
  s.stages = {stage("I", {kCpu1}, 1, kRetrace, true), stage("S", {kCpu1}, 8), stage("R", {kCpu2}, 9, kRetrace),
              stage("G", {kGpu}, 10)};
  check_range(s, 48.0, 48.0 + kLastLine);
}

TEST_CASE("reference: minimal GPU buffering draws while the commands are issued") {
  // GPU : |-GGGGGGGGGG-----| : G starts 1 ms after R, shown from V_{k+2}: 32 - 48 ms.
  FrameStagesSpec s = base({"cpu1", "cpu2", "gpu"}, 2);
  s.stages = {stage("I", {kCpu1}, 1, kRetrace, true), stage("S", {kCpu1}, 8), stage("R", {kCpu2}, 9, kRetrace),
              streaming("G", {kGpu}, 10, 1)};
  check_range(s, 32.0, 32.0 + kLastLine);
}

TEST_CASE("reference: alternate frame rendering on two GPUs of twice the frame time") {
  // GPU1: | GGG...(24) shown from V_{k+3}: 48 - 64 ms; three swap-chain images.
  FrameStagesSpec s = base({"cpu1", "cpu2", "gpu1", "gpu2"}, 4);
  s.swap_chain_images = 3;
  s.stages = {stage("I", {kCpu1}, 1, kRetrace, true), stage("S", {kCpu1}, 8), stage("R", {kCpu2}, 9, kRetrace),
              streaming("G", {2, 3}, 24, 1)};
  Rig rig(s);
  rig.run(1.0);
  CHECK(rig.mtp("min") == Approx(48.0).margin(1e-6));
  CHECK(rig.mtp("max") == Approx(48.0 + kLastLine).margin(1e-6));
  CHECK(rig.figures["frames_missed"].get<int64_t>() == 0);
}

TEST_CASE("reference: late frame scheduling reads the input in the last millisecond before the retrace") {
  // CPU1:SSSSSSSSS------I| : I at V_{k+1} - 1, shown from V_{k+2}: 17 - 33 ms
  // (the article prints 18 - 34, counting a character for the bar).
  FrameStagesSpec s = base({"cpu1", "cpu2", "gpu"}, 3);
  s.stages = {stage("S", {kCpu1}, 9, kRetrace), stage("I", {kCpu1}, 1, kLate, true),
              stage("R", {kCpu2}, 9, kRetrace), streaming("G", {kGpu}, 10, 1)};
  check_range(s, 17.0, 17.0 + kLastLine);
}

TEST_CASE("reference: view bypass samples the view again before render submission") {
  // CPU2: |IRRRRRRRRR : the view read at V_{k+1}, shown from V_{k+2}: 16 - 32 ms.
  FrameStagesSpec s = base({"cpu1", "cpu2", "gpu"}, 3);
  s.stages = {stage("I", {kCpu1}, 1, kRetrace, true), stage("S", {kCpu1}, 9),
              stage("I2", {kCpu2}, 1, kRetrace, true), stage("R", {kCpu2}, 9), streaming("G", {kGpu}, 10, 1)};
  check_range(s, 16.0, 16.0 + kLastLine);
}

TEST_CASE("reference: late-sampled view bypass reads the view as late as drawing allows") {
  // CPU2: |----IRRRRRRRRR--| GPU: |------GGGGGGGGGG| : the span from I to the
  // end of G is 12 ms, so I starts at V_{k+2} - 12: 12 - 28 ms.
  FrameStagesSpec s = base({"cpu1", "cpu2", "gpu"}, 3);
  StageSpec i2 = stage("I2", {kCpu2}, 1, kLate, true);
  i2.until = 4;
  s.stages = {stage("I", {kCpu1}, 1, kRetrace, true), stage("S", {kCpu1}, 9), i2, stage("R", {kCpu2}, 9),
              streaming("G", {kGpu}, 10, 1)};
  check_range(s, 12.0, 12.0 + kLastLine);
}

TEST_CASE("reference: tiler-optimized view bypass writes the view into a buffer just before drawing") {
  // CPU2: |IRRRRRRRRRR-----|I  GPU: | |-GGGGGGGGGG : commands issued a frame
  // ahead; at V_{k+2} the view is written (I, 1 ms) and G draws from V_{k+2} + 1,
  // shown from V_{k+3}: 16 - 32 ms.
  FrameStagesSpec s = base({"cpu1", "cpu2", "input", "gpu"}, 3);
  s.stages = {stage("I", {kCpu1}, 1, kRetrace, true), stage("S", {kCpu1}, 9), stage("R", {kCpu2}, 10, kRetrace),
              stage("IV", {2}, 1, kRetrace, true), stage("G", {3}, 10)};
  check_range(s, 16.0, 16.0 + kLastLine);
}

TEST_CASE("reference: late-scheduled time warp re-projects the finished image 2 ms before the retrace") {
  // CPU2: |RRRRRRRRRR----IR| GPU : |-GGGGGGGGGG----G| : the warp reads the pose at
  // V - 2 and re-projects with depth (orientation and position): 2 - 18 ms.
  FrameStagesSpec s = base({"cpu1", "cpu2", "gpu"}, 2);
  s.stages = {stage("I", {kCpu1}, 1, kRetrace, true), stage("S", {kCpu1}, 9), stage("R", {kCpu2}, 10, kRetrace),
              streaming("G", {kGpu}, 10, 1)};
  WarpSpec w;
  w.mode = WarpSpec::Mode::positional;
  StageSpec wi = stage("WI", {kCpu2}, 1, kLate, true);
  wi.until = 2;
  w.stages = {wi, stage("WR", {kCpu2}, 1), streaming("W", {kGpu}, 1, 0)};
  s.warp = w;
  Rig rig(s);
  rig.run(1.0);
  CHECK(rig.mtp("min") == Approx(2.0).margin(1e-6));
  CHECK(rig.mtp("max") == Approx(2.0 + kLastLine).margin(1e-6));
  CHECK(rig.figures["frames_missed"].get<int64_t>() == 0);
  CHECK(rig.figures["warps_late"].get<int64_t>() == 0);
}

namespace {
/// Continuous time warp: a positional warp on its own processor, 8 strips a
/// refresh, each warped in the millisecond before its first line.
FrameStagesSpec continuous_warp() {
  FrameStagesSpec s = base({"cpu1", "cpu2", "gpu", "warp"}, 2);
  s.stages = {stage("I", {kCpu1}, 1, kRetrace, true), stage("S", {kCpu1}, 9), stage("R", {kCpu2}, 11, kRetrace),
              streaming("G", {kGpu}, 12, 1)};
  WarpSpec w;
  w.mode = WarpSpec::Mode::positional;
  w.strips = 8;
  w.stages = {stage("W", {3}, 1, kLate, true)};
  s.warp = w;
  return s;
}
}  // namespace

TEST_CASE("reference: continuous time warp warps 2 ms strips just ahead of the beam") {
  // WARP: |               W| W W W W W W W W| : strip s of a refresh is warped
  // in the millisecond before its first line; a line d into its 2 ms strip is
  // lit 1 + d after the warp read a pose 1 ms old: 2 - 3.9 ms.
  const FrameStagesSpec s = continuous_warp();
  check_range(s, 2.0, 2.0 + 1.9, 500);
}

TEST_CASE("reference: displays from 59.94 to 144 Hz hold one refresh of latency plus the scanout") {
  // The vsync configuration on the refresh rates of today's headsets (SPEC
  // section 10: 60, 72, 75, 80, 90, 120, 144 Hz) and NTSC's 59.94 Hz, most of
  // whose periods (1/72 s, 1/144 s, 1001/60000 s) are no whole number of
  // picoseconds: the pose read at a retrace (up to 1 ms old: the retraces no
  // longer fall on whole milliseconds), shown from the next one, the bottom
  // line 159/160 of a refresh later: min in [T, T + 1), max in
  // [T + 159 T / 160, that + 1); a new frame every refresh (I and G take
  // 1.5 ms, less than the shortest period, 6.94 ms).
  for (const auto& [num, den] : {std::pair<int64_t, int64_t>{60, 1}, {72, 1}, {75, 1}, {80, 1}, {90, 1}, {120, 1},
                                  {144, 1}, {60000, 1001}}) {
    FrameStagesSpec s = base({"cpu", "gpu"}, 2);
    s.stages = {stage("I", {0}, 0.5, kRetrace, true), stage("G", {1}, 1)};
    latsim::testing::RigOptions o;
    o.field_period = latsim::des::RationalSeconds::period_of_hz(num, den);
    Rig rig(s, o);
    rig.run(2.0);
    const double t_ms = 1000.0 * static_cast<double>(den) / static_cast<double>(num);
    INFO(t_ms);
    CHECK(rig.mtp("min") >= t_ms - 1e-6);
    CHECK(rig.mtp("min") < t_ms + 1.0);
    CHECK(rig.mtp("max") >= t_ms * (1.0 + 159.0 / 160.0) - 1e-6);
    CHECK(rig.mtp("max") < t_ms * (1.0 + 159.0 / 160.0) + 1.0);
    CHECK(rig.figures["frames_missed"].get<int64_t>() == 0);
    CHECK(rig.figures["application_frame_rate_hz"].get<double>() == Approx(1000.0 / t_ms).margin(1.0));
  }
}

TEST_CASE("reference: an hour of late-sampled view bypass keeps the exact range") {
  // Late scheduling aims at retraces computed from their index: after an hour
  // (225,000 refreshes) the view is still read exactly 12 ms before the
  // retrace that shows it. Two lines keep the hour cheap: the bottom one is lit
  // 8 ms after the top one.
  FrameStagesSpec s = base({"cpu1", "cpu2", "gpu"}, 3);
  StageSpec i2 = stage("I2", {kCpu2}, 1, kLate, true);
  i2.until = 4;
  s.stages = {stage("I", {kCpu1}, 1, kRetrace, true), stage("S", {kCpu1}, 9), i2, stage("R", {kCpu2}, 9),
              streaming("G", {kGpu}, 10, 1)};
  latsim::testing::RigOptions o;
  o.lines = 2;
  Rig rig(s, o);
  rig.run(3600.0);
  CHECK(rig.mtp("min") == Approx(12.0).margin(1e-6));
  CHECK(rig.mtp("max") == Approx(20.0).margin(1e-6));
  CHECK(rig.figures["frames_missed"].get<int64_t>() == 0);
  CHECK(rig.figures["frames_rendered"].get<int64_t>() >= 225000 - 3);
}

TEST_CASE("reference: an hour of continuous time warp keeps every strip on its line") {
  // The continuous time warp above on 16 lines of 1 ms (8 strips of two
  // lines) for an hour: 1.8 million strips, each aimed at its first line's
  // instant computed from the refresh and strip index. Strip s of a refresh
  // is warped from V + 2s - 1 (a 500 Hz sample taken 1 ms earlier, on an
  // even millisecond) to V + 2s, when its first line is lit; its second line
  // is lit 1 ms later: 2 - 3 ms, every strip on time. Frame 0 completes at
  // 29 ms (G streams from 17 for 12 ms), so the first strip warped is the one
  // due at 30 ms (strip 7 of refresh 1); then every strip of refreshes 2 to
  // 224,999, and strip 0 of refresh 225,000, due at the end instant:
  // 1 + 8 x 224,998 + 1 = 1,799,986 warps.
  const FrameStagesSpec s = continuous_warp();
  latsim::testing::RigOptions o;
  o.tracker_hz = 500;
  o.lines = 16;
  Rig rig(s, o);
  rig.run(3600.0);
  CHECK(rig.mtp("min") == Approx(2.0).margin(1e-6));
  CHECK(rig.mtp("max") == Approx(3.0).margin(1e-6));
  CHECK(rig.figures["warps"].get<int64_t>() == 1799986);
  CHECK(rig.figures["warps_late"].get<int64_t>() == 0);
  CHECK(rig.figures["frames_missed"].get<int64_t>() == 0);
}
