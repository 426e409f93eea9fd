// Rendering Control's swap and copy rules examined against the published
// fly-through spreads and the minimum case (docs/pxpl5.md, "What could spread
// a small model's latency"): swaps only at a frame's start, each eye's buffer
// swapped on its own, and copies that hold a renderer. Each is checked
// against a recurrence written here from the rule, not from the engine.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "harness.hpp"

using namespace latsim;
using namespace latsim::pxpl5;
using namespace latsim::pxpl5::testing;

namespace {

// The first retrace strictly after t; with frame_start, the first of a frame (an even field).
int64_t allowed_field_after(des::Time t, bool frame_start) {
  const FieldTiming timing = ntsc_timing();
  int64_t k = timing.field_after(t);
  if (frame_start && k % 2 != 0) ++k;
  return k;
}

// One eye's COPY of a frame as the engine ran it: the first region's start and the last one's end.
struct CopySpan {
  des::Time start, end;
};

CopySpan copy_span(const RunRecord& r, int64_t frame, int eye) {
  CopySpan span{des::Time::max(), des::Time::zero()};
  for (const StageInterval& s : r.stages)
    if (s.stage == "COPY" && s.frame == frame && s.eye == eye && s.unit.rfind("FB", 0) == 0) {
      span.start = std::min(span.start, s.start);
      span.end = std::max(span.end, s.end);
    }
  return span;
}

// A host that takes 40 ms per frame and nothing else but COPY (780 us x 20
// regions x 2 eyes) costs anything: the processors wait for the host, not for
// COPY. By hand: EDIT and both TRANSFORMs end with SEND, at T(i) = 40 (i + 1)
// ms; COPY of both eyes starts at max(T(i), S(i - 1)), once the previous frame
// is swapped in, and takes 31.2 ms; the frame swaps at S(i), the first allowed
// retrace after that. Both eyes' latency is S(i) - T(i).
std::vector<double> host_bound_by_hand(int frames, bool frame_start, des::Time period = des::Time::ms(40),
                                       int64_t first = 1) {
  const FieldTiming timing = ntsc_timing();
  std::vector<double> fields;
  des::Time previous_swap = des::Time::zero();
  for (int i = 0; i < frames; ++i) {
    const des::Time t = period * (i + first);
    const des::Time copy_end = std::max(t, previous_swap) + des::Time::us(780) * 40;
    previous_swap = timing.retrace(allowed_field_after(copy_end, frame_start));
    fields.push_back((previous_swap - t).to_ms() / timing.period_ms());
  }
  return fields;
}

RunRecord host_bound_run(SwapAt swap_at) {
  RcParams p = trivial_rc_params();
  p.send_time = des::Time::ms(40);
  p.swap_at = swap_at;
  return run_rc(p, Workload{0, 1.0}, des::Time::s(3));
}

}  // namespace

TEST_CASE("frame-start swaps: a host-bound frame waits for the retrace that starts a frame", "[pxpl5][rc][swap]") {
  for (const bool frame_start : {false, true}) {
    const RunRecord r = host_bound_run(frame_start ? SwapAt::frame_start : SwapAt::any_field);
    const std::vector<double> hand = host_bound_by_hand(static_cast<int>(r.frames.size()), frame_start);
    REQUIRE(r.frames.size() > 60);
    const FieldTiming timing = ntsc_timing();
    for (std::size_t i = 0; i < r.frames.size(); ++i) {
      const FrameReady& f = r.frames[i];
      CHECK((f.swap_at - f.eyes[0].transform_start).to_ms() / r.field_ms == Approx(hand[i]).margin(1e-9));
      CHECK((f.swap_at - f.eyes[1].transform_start).to_ms() / r.field_ms == Approx(hand[i]).margin(1e-9));
      if (frame_start) CHECK(f.swap_field % 2 == 0);
      // The display is handed the frame after the retrace before its swap, so its next retrace is the swap.
      CHECK(r.frame_ready_at[i] > timing.retrace(f.swap_field - 1));
      CHECK(r.frame_ready_at[i] < f.swap_at);
    }
    // Any field: the latency is 31.2 ms plus a wait for the next retrace
    // (1.87 to 2.87 fields); frame start: up to two fields of wait.
    const auto [lo, hi] = std::minmax_element(hand.begin(), hand.end());
    CHECK(*lo >= 31.2 / r.field_ms);
    CHECK(*hi < 31.2 / r.field_ms + (frame_start ? 2.0 : 1.0));
  }
}

// Each eye's frame buffer swapped at the first retrace after its own COPY
// (SPEC.md section 4 swaps both together). In the minimum case COPY then runs
// eye after eye, L R L R, each 15.6 ms, and an eye's COPY waits only for its
// own buffer's previous swap: C(k) = max(C(k - 1), S(k - 2)) + 15.6 ms, S(k)
// the first retrace after C(k). The left eye's TRANSFORM starts 0.2 ms (EDIT)
// after the previous-but-one frame's right COPY ends, the right eye's when
// the previous frame's left COPY ends (COPY three eyes back, as before).
TEST_CASE("per-eye swaps: the minimum case's copies follow the recurrence by hand", "[pxpl5][rc][swap]") {
  RcParams p;
  p.stereo_swap = StereoSwap::per_eye;
  const RunRecord r = run_rc(p, Workload{12, 20.0}, des::Time::s(4));
  const FieldTiming timing = ntsc_timing();
  // The pipeline fills by frame 2; from there the recurrence runs on its own.
  const int64_t first = 2, last = 100;
  std::vector<des::Time> copy_end, swap;  // by eye sequence k = 2 frame + eye, from 2 first
  copy_end.push_back(copy_span(r, first, 0).end);
  copy_end.push_back(copy_span(r, first, 1).end);
  for (const des::Time c : copy_end) swap.push_back(timing.retrace(timing.field_after(c)));
  for (int64_t k = 2; k < 2 * (last - first + 1); ++k) {
    const des::Time c = std::max(copy_end[static_cast<std::size_t>(k - 1)], swap[static_cast<std::size_t>(k - 2)]) +
                        des::Time::us(780) * 20;
    copy_end.push_back(c);
    swap.push_back(timing.retrace(timing.field_after(c)));
  }
  std::vector<double> left, right;
  for (int64_t i = first + 2; i <= last; ++i) {
    const auto at = [&](int64_t frame, int eye) { return static_cast<std::size_t>(2 * (frame - first) + eye); };
    CHECK(copy_span(r, i, 0).end == copy_end[at(i, 0)]);
    CHECK(copy_span(r, i, 1).end == copy_end[at(i, 1)]);
    left.push_back((swap[at(i, 0)] - copy_end[at(i - 2, 1)] - des::Time::us(200)).to_ms() / r.field_ms);
    right.push_back((swap[at(i, 1)] - copy_end[at(i - 1, 0)]).to_ms() / r.field_ms);
  }
  // The engine's per-eye figures over the same frames.
  std::vector<double> engine_left, engine_right;
  for (const FrameReady& f : r.frames) {
    if (f.frame < first + 2 || f.frame > last) continue;
    for (const EyeImage& e : f.eyes)
      (e.eye == 0 ? engine_left : engine_right).push_back((f.swap_at - e.transform_start).to_ms() / r.field_ms);
  }
  REQUIRE(engine_left.size() == left.size());
  REQUIRE(engine_right.size() == right.size());
  for (std::size_t j = 0; j < left.size(); ++j) {
    CHECK(engine_left[j] == Approx(left[j]).margin(1e-9));
    CHECK(engine_right[j] == Approx(right[j]).margin(1e-9));
  }
  // Three eyes' copies (46.8 ms, 2.81 fields) and the wait for a retrace: each
  // eye between 2.8 and 3.9 fields; the published minimum case is 3.4.
  for (const double v : left) CHECK((v > 2.79 && v < 3.9));
  for (const double v : right) CHECK((v > 2.8 && v < 3.9));
}

// One renderer, the minimum case: per stereo frame it renders 40 regions of
// about 0.38 ms each (12 token hops of 5 us with a 24-word bin, the
// end-of-frame words and 300 us of shading: docs/pxpl5.md, point 1), 15.3 ms,
// and the 40 copies take 31.2 ms. When a copy holds the renderer, the two
// cannot overlap: 46.5 ms of renderer time per frame, more than two fields,
// so frames come on average at least 46.5 ms apart instead of every two fields.
TEST_CASE("copies that hold the renderer: one renderer can no longer keep up with two fields", "[pxpl5][rc][copy]") {
  RcParams p;
  p.hw.renderers = 1;
  const RunRecord free_renderer = run_rc(p, Workload{12, 20.0}, des::Time::s(3));
  p.copy_holds_renderer = true;
  const RunRecord held = run_rc(p, Workload{12, 20.0}, des::Time::s(3));
  const double two_fields = 2000.0 / 60.0;
  CHECK(free_renderer.dist("frame_time_ms").summary().max == Approx(two_fields).margin(1e-6));
  CHECK(held.dist("frame_time_ms").summary().mean >= 46.0);
  // On the renderer, no copy overlaps a region being rendered.
  std::vector<const StageInterval*> render, copy;
  for (const StageInterval& s : held.stages) {
    if (s.unit != "R0") continue;
    (s.stage == "RENDER" ? render : copy).push_back(&s);
  }
  REQUIRE(copy.size() > 40);
  int64_t overlaps = 0;
  for (const StageInterval* c : copy)
    for (const StageInterval* g : render) overlaps += (c->end <= g->start || g->end <= c->start) ? 0 : 1;
  CHECK(overlaps == 0);
}

// A host that blocks until the tracker has a sample newer than the last
// frame's, with a 20 Hz tracker (sample k visible at k x 50 ms) and the
// processors costing nothing but COPY: SEND of frame i waits for sample i,
// so by hand T(i) = 50 i ms, and the frames follow the recurrence of the
// host-bound case above with a 50 ms period. Latency 31.2 ms plus the wait
// for a retrace: the host's pace lowers it from the full pipeline's.
TEST_CASE("a host that waits for a new tracker sample paces the frames at the tracker's rate", "[pxpl5][rc][host]") {
  RcParams p = trivial_rc_params();
  p.host_waits_for_new_sample = true;
  const RunRecord r = run_rc_with_tracker(p, Workload{0, 1.0}, des::Time::s(3), des::RationalSeconds{1, 20});
  const std::vector<double> hand = host_bound_by_hand(static_cast<int>(r.frames.size()), false, des::Time::ms(50), 0);
  REQUIRE(r.frames.size() > 50);
  for (std::size_t i = 0; i < r.frames.size(); ++i) {
    CHECK(r.frames[i].eyes[0].sample_token == static_cast<int64_t>(i));
    CHECK((r.frames[i].swap_at - r.frames[i].eyes[0].transform_start).to_ms() / r.field_ms ==
          Approx(hand[i]).margin(1e-9));
  }
  // Without the wait the same host runs the pipeline full, COPY-bound: one frame every two fields.
  p.host_waits_for_new_sample = false;
  const RunRecord full = run_rc_with_tracker(p, Workload{0, 1.0}, des::Time::s(3), des::RationalSeconds{1, 20});
  CHECK(full.dist("frame_time_ms").summary().mean == Approx(2000.0 / 60.0).margin(1e-6));
}
