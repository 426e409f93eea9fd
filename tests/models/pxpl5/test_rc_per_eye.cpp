// Rendering Control per eye: TRANSFORM start to the swap of each eye, against
// the published measurement of the minimum case, and what spheres cost.
#include <catch2/catch.hpp>

#include <algorithm>
#include <vector>

#include "harness.hpp"
#include "latsim/pxpl5/view_workload.hpp"

using namespace latsim;
using namespace latsim::pxpl5;
using namespace latsim::pxpl5::testing;

// The minimum case (12 full-screen triangles, SPEC.md section 4) is
// COPY-bound: a stereo frame's COPY is 40 x 0.78 = 31.2 ms, so frames swap
// every two fields (33.333 ms) and each frame's COPY ends 2.133 ms before its
// swap. By hand, with S(i) the swap of frame i:
// - EDIT(i) and the left eye's TRANSFORM wait for COPY three eyes back, the
//   right eye of frame i - 2, which ends at S(i-2) - 2.133 ms; EDIT takes
//   0.2 ms. Left: S(i) - (S(i-2) - 1.933 ms) = 66.667 + 1.933 = 68.600 ms,
//   4.116 fields.
// - The right eye's TRANSFORM waits for COPY of the left eye of frame i - 1,
//   which starts at S(i-2) and ends 15.6 ms later. Right: 66.667 - 15.6 =
//   51.067 ms, 3.064 fields.
// The published measurement of the same machine, TRANSFORM start to the
// swap, is 3.4 fields: the left eye (whose TRANSFORM first uses the frame's
// tracking data) is 0.716 fields above it, the right 0.336 below, their mean
// (3.590) 0.190 above.
TEST_CASE("the minimum case per eye, TRANSFORM start to the swap, against the published 3.4 fields", "[pxpl5][rc][calibration]") {
  const double field_ms = 1000.0 / 60.0;
  const double left_hand = (4 * field_ms + (2 * field_ms - 31.2) - 0.2) / field_ms;
  const double right_hand = (4 * field_ms - 15.6) / field_ms;
  CHECK(left_hand == Approx(4.116).margin(5e-4));
  CHECK(right_hand == Approx(3.064).margin(5e-4));
  const RunRecord r = run_rc(RcParams{}, Workload{12, 20.0}, des::Time::s(4));
  // Every frame but the first few, which fill the pipeline, from the frames themselves.
  REQUIRE(r.frames.size() > 100);
  for (std::size_t i = 4; i < r.frames.size(); ++i) {
    const FrameReady& f = r.frames[i];
    CHECK((f.swap_at - f.eyes[0].transform_start).to_ms() / field_ms == Approx(left_hand).margin(1e-3));
    CHECK((f.swap_at - f.eyes[1].transform_start).to_ms() / field_ms == Approx(right_hand).margin(1e-3));
  }
  // The figures carry the same, one distribution per eye.
  const auto left = r.dist("transform_to_swap_fields.left").summary();
  const auto right = r.dist("transform_to_swap_fields.right").summary();
  CHECK(left.count == r.frames.size());
  CHECK(left.max == Approx(left_hand).margin(1e-3));
  CHECK(right.max == Approx(right_hand).margin(1e-3));
  CHECK(left.mean == Approx(left_hand).margin(0.05));
  CHECK(right.mean == Approx(right_hand).margin(0.05));
  constexpr double published = 3.4;
  CHECK(left_hand - published == Approx(0.716).margin(5e-4));
  CHECK(right_hand - published == Approx(-0.336).margin(5e-4));
  // The pool of both eyes: a two-valued distribution, a field apart, whose
  // spread is half the gap between them.
  const auto pooled = r.dist("transform_to_retrace_fields").summary();
  CHECK(pooled.count == 2 * left.count);
  CHECK(pooled.stddev == Approx((left_hand - right_hand) / 2).margin(0.05));
}

TEST_CASE("mono RC reports one eye under its own name", "[pxpl5][rc]") {
  RcParams mono;
  mono.stereo = false;
  const RunRecord r = run_rc(mono, Workload{12, 20.0}, des::Time::s(1));
  CHECK(r.samples.count("transform_to_swap_fields.mono") == 1);
  CHECK(r.samples.count("transform_to_swap_fields.left") == 0);
}

// Twelve small spheres in front (one per slave, each inside region 0 of the
// 640 x 480 screen at 60 degrees), twelve triangles and twelve spheres
// behind. Per slave and eye, TRANSFORM = 100 us of set-up + 15 us for its
// sphere on screen + 5 us for that sphere's one bin entry + 3.75 us to reject
// its triangle + 1.25 us to reject its other sphere = 125 us. Region 0's
// RENDER: the token's 12 hops of 5 us, each slave's 30-word sphere command on
// the ring (1.5 us) and rendered (3.8 us) while the token moves on, the
// end-of-frame words (1.6 us), 300 us of shading once the last command is
// rendered, and the hop back: the last command arrives at 12 x 6.5 = 78 us,
// is rendered by 81.8 us, shading ends at 381.8 us.
TEST_CASE("a sphere costs its own TRANSFORM, ring words and RENDER", "[pxpl5][rc][spheres]") {
  ViewScreen screen;  // 60 degrees: tan 30 = 0.5774 across, 0.4330 up
  const double d = 2.0, x = d * 0.57735 * (64.0 / 320.0 - 1.0), y = d * 0.43301 * (1.0 - 64.0 / 240.0);
  std::vector<WorldTriangle> triangles(12, WorldTriangle{glm::dvec3(0, 0, 2), glm::dvec3(0.1, 0, 2), glm::dvec3(0, 0.1, 2)});
  std::vector<WorldSphere> spheres(12, WorldSphere{glm::dvec3(x, y, -d), 0.05});
  spheres.resize(24, WorldSphere{glm::dvec3(0, 0, 3), 0.05});
  // Display list: triangles 0-11, then spheres at 12-23 (in front) and 24-35 (behind): one of each per slave.
  const auto still = [](int64_t, int) { return tracker::Pose{}; };
  ViewWorkload work(ViewBinner(triangles, screen, spheres), still);
  const RunRecord r = run_rc(RcParams{}, work, des::Time::ms(300));
  CHECK(r.dist("stage_ms.TRANSFORM").summary().max == Approx(0.125).margin(1e-9));
  CHECK(r.dist("stage_ms.TRANSFORM").summary().min == Approx(0.125).margin(1e-9));
  CHECK(r.dist("spheres_on_screen").summary().mean == 12.0);
  CHECK(r.dist("triangles_on_screen").summary().max == 0.0);
  CHECK(r.dist("regions_per_primitive").summary().mean == 1.0);
  // The busiest region goes first, to R0: region 0, 381.8 us.
  const auto first = std::find_if(r.stages.begin(), r.stages.end(),
                                  [](const StageInterval& s) { return s.stage == "RENDER" && s.unit == "R0"; });
  REQUIRE(first != r.stages.end());
  CHECK((first->end - first->start).to_ms() * 1000.0 == Approx(381.8).margin(1e-6));
}
