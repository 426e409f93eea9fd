// The parts of the staged pipeline on their own: progress counters, late
// scheduling's span estimate, the compositor's deadlines, and late
// scheduling against stage durations that vary.
#include <catch2/catch.hpp>

#include <vector>

#include "frame_stages/progress.hpp"
#include "frame_stages/span_estimate.hpp"
#include "frame_stages/warp_clock.hpp"
#include "latsim/des/process.hpp"
#include "rig.hpp"

using latsim::des::Process;
using latsim::des::Simulator;
using latsim::des::Time;
using namespace latsim::pipelines::frame_stages;

namespace {

Process wait_for(Simulator& sim, Progress& p, int64_t target, std::vector<std::pair<int64_t, Time>>& log) {
  co_await p.reached(target);
  log.emplace_back(target, sim.now());
}

latsim::display::RasterTiming timing_16ms(int vblank) {
  latsim::display::RasterParams p;
  p.field_period = latsim::des::RationalSeconds::period_of_hz(125, 2);
  p.width_px = 10;
  p.height_px = 160;
  p.vblank_lines = vblank;
  p.hblank_px = 0;
  return latsim::display::RasterTiming(p);
}

}  // namespace

TEST_CASE("progress: waiters resume when the value reaches their target, in the order they began waiting") {
  Simulator sim;
  Progress p(sim);
  std::vector<std::pair<int64_t, Time>> log;
  sim.spawn(wait_for(sim, p, 2, log));
  sim.spawn(wait_for(sim, p, 1, log));
  sim.spawn(wait_for(sim, p, 0, log));  // already reached: continues at once
  sim.at(Time::ms(5), sim.kind("test.raise"), [&] { p.advance(); });
  sim.at(Time::ms(7), sim.kind("test.raise"), [&] { p.raise_to(3); });
  sim.run();
  REQUIRE(log.size() == 3);
  CHECK(log[0] == std::make_pair(int64_t{0}, Time::zero()));
  CHECK(log[1] == std::make_pair(int64_t{1}, Time::ms(5)));
  CHECK(log[2] == std::make_pair(int64_t{2}, Time::ms(7)));
}

TEST_CASE("progress: a prefix counts jobs done without a gap whatever the order they finish in") {
  Simulator sim;
  PrefixProgress p(sim);
  p.mark(1);
  p.mark(2);
  CHECK(p.value() == 0);
  p.mark(0);
  CHECK(p.value() == 3);
  p.mark(1);  // again: no effect
  CHECK(p.value() == 3);
}

TEST_CASE("span estimate: the longest of the nominal span and the last measured ones") {
  SpanEstimate e(Time::ms(2), 3);
  CHECK(e.estimate() == Time::ms(2));
  e.add(Time::ms(3));
  e.add(Time::ms(1));
  CHECK(e.estimate() == Time::ms(3));
  e.add(Time::ms(1));
  e.add(Time::ms(1));  // the 3 ms span has left the window of three
  CHECK(e.estimate() == Time::ms(2));
}

TEST_CASE("warp clock: one strip is due at each retrace, strips when their first line is lit") {
  const auto t = timing_16ms(0);
  const WarpClock whole(t, 1);
  CHECK(whole.next_deadline(Time::ms(3)) == Time::ms(16));
  CHECK(whole.next_deadline(Time::ms(16)) == Time::ms(16));
  CHECK(whole.middle_line(whole.slot_of(Time::ms(16)).strip) == 79);
  // 160 lines of 0.1 ms in 8 strips of 20 lines (2 ms): strip s of field 1 at 16 + 2 s ms.
  const WarpClock strips(t, 8);
  CHECK(strips.first_line(3) == 60);
  CHECK(strips.next_deadline(Time::from_ms(21.5)) == Time::ms(22));
  CHECK(strips.next_deadline(Time::from_ms(30.5)) == Time::ms(32));  // past strip 7: next field's strip 0
  const WarpClock::Slot s = strips.slot_of(Time::ms(22));
  CHECK(s.field == 1);
  CHECK(s.strip == 3);
  CHECK(strips.middle_line(s.strip) == 69);
  // With blanking a strip's deadline is its first line, after the retrace.
  const auto tb = timing_16ms(40);  // 200 line periods of 0.08 ms: 40 blank, then 160 active
  CHECK(WarpClock(tb, 8).next_deadline(Time::ms(16)) == Time::from_ms(16 + 40 * 0.08));
  CHECK(WarpClock(tb, 1).next_deadline(Time::from_ms(0.5)) == Time::ms(16));
}

TEST_CASE("late scheduling gives a stage whose time varies the longest time it recently took") {
  // I (1 ms +-30 %, uniform) is late-scheduled to end at the retrace where
  // the render thread takes the frame. The estimate is the largest of the
  // nominal 1 ms and the last 8 measured durations, so a frame misses its
  // refresh when its I is the longest of nine draws in a row (and above 1 ms):
  // a chance of 1/9, whatever the distribution. Over 623 frames that is 69
  // misses, give or take 8 (binomial standard deviation).
  using latsim::testing::Rig;
  using latsim::testing::stage;
  FrameStagesSpec s;
  s.processors = {ProcessorSpec{"cpu1", {}}, ProcessorSpec{"cpu2", {}}, ProcessorSpec{"gpu", {}}};
  s.max_frames_in_flight = 3;
  StageSpec i = stage("I", {0}, 1, StartRule::late, true);
  latsim::renderer::RenderCost::Params varied;
  varied.fixed_ms = 1;
  varied.variation = latsim::renderer::RenderCost::Variation::Uniform;
  varied.variation_fraction = 0.3;
  i.cost = latsim::renderer::RenderCost(varied, 0, 0);
  s.stages = {stage("S", {0}, 9, StartRule::retrace), i, stage("R", {1}, 9, StartRule::retrace), stage("G", {2}, 1)};
  Rig rig(s);
  rig.run(10.0);
  const int64_t frames = rig.figures["frames_rendered"].get<int64_t>();
  const int64_t missed = rig.figures["frames_missed"].get<int64_t>();
  CHECK(missed > 69 - 4 * 8);
  CHECK(missed < 69 + 4 * 8);
  // Every one of the 625 refreshes shows a new frame or counts a miss (the
  // first two come before the first frame is shown, the last frames in
  // flight at the end are rendered but not shown).
  CHECK(frames + missed >= 625 - 2);
  CHECK(frames + missed <= 625 + 1);
  UNSCOPED_INFO("frames " << frames << ", missed " << missed);
  // Read at most 1.3 ms and at least 0.7 ms (at worst) before the retrace:
  // motion-to-photon of the top line between 16.7 and 17.3 ms, unless the
  // frame slipped a refresh.
  CHECK(rig.mtp("min") >= 16.7 - 1e-6);
}
