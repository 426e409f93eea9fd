// Application pacing policies against hand derivations: Monado's IIR
// convergence, its transient after a step in GPU time, and the latency that
// pacing saves on a light workload (docs/pacing.md).
#include <catch2/catch.hpp>

#include <cmath>

#include "rig.hpp"

using latsim::testing::Rig;
using latsim::testing::RigOptions;
using latsim::testing::stage;
using namespace latsim::pipelines::frame_stages;
using latsim::des::Time;

namespace {

/// C (CPU, reads the pose), R (render thread: the draw span), G (GPU), each
/// on its own processor and started when the previous ends; no compositor.
/// Three swap-chain images: one shown, one queued, one drawn into, so that a
/// frame never waits for an image.
FrameStagesSpec three_spans(double cpu_ms, double draw_ms, double gpu_ms, int in_flight) {
  FrameStagesSpec s;
  s.swap_chain_images = 3;
  s.processors = {ProcessorSpec{"cpu", {}}, ProcessorSpec{"render", {}}, ProcessorSpec{"gpu", {}}};
  s.max_frames_in_flight = in_flight;
  s.stages = {stage("C", {0}, cpu_ms, StartRule::retrace, true), stage("R", {1}, draw_ms), stage("G", {2}, gpu_ms)};
  s.pacing.app = AppPolicy::monado;
  return s;
}

double ms(Time t) { return t.to_ms(); }

}  // namespace

TEST_CASE("pacing: Monado's estimates converge as 0.8^n from 2, 2 and 0 ms and settle on the hand-derived wake-up") {
  // 62.5 Hz (retraces every 16 ms), no compositor: a frame is shown at the
  // first retrace after it is done, so the latch is the retrace itself.
  // C 3 ms, R 2 ms, G 4 ms; one frame in flight, so frame n is planned once
  // frames 0 .. n-1 are measured (n samples). The cpu span is C (woken to R's
  // start), draw R, gpu G. Monado's pa_create sets the CPU and draw
  // estimates to 2 ms and leaves the GPU estimate at zero, so after n samples
  //   cpu 3 - 1 * 0.8^n, draw 2, gpu 4 - 4 * 0.8^n  => app_n = 9 - 5 * 0.8^n ms.
  // Frame n wakes at D_n - 2 (margin) - app_n, runs 9 ms without waiting, so
  // it is done 9 - app_n = 5 * 0.8^n after its prediction and 2 - 5 * 0.8^n
  // before its latch: frames 0 .. 4 miss (5, 4, 3.2, 2.56, 2.048 > 2), frame
  // 5 (1.638) and all later ones make it. D_0 = 16 (the first retrace
  // leaving app_0 + 2 = 6 ms after t = 0); frame n is planned when frame
  // n - 1 is done, at D_(n-1) - 2 + 5 * 0.8^(n-1), and needs app_n + 2 ms:
  // D_(n-1) + 9 + 0.8^(n-1) at most 10 ms on, so the next retrace, 16 ms on.
  // So D_n = 16 (n + 1) and wake_n = 16 (n + 1) - 11 + 5 * 0.8^n.
  Rig rig(three_spans(3, 2, 4, 1));
  rig.run(1.0);
  const AppPacing* pacing = rig.pipeline.app_pacing();
  REQUIRE(pacing != nullptr);
  const auto& log = pacing->log();
  REQUIRE(log.size() >= 60);
  for (size_t n = 0; n < 60; ++n) {
    INFO("frame " << n);
    const double decay = std::pow(0.8, static_cast<double>(n));
    const PacedFrame& f = log[n];
    CHECK(f.job == static_cast<int64_t>(n));
    CHECK(ms(f.sample.gpu_done - f.plan.predicted_done) == Approx(5.0 * decay).margin(1e-6));
    CHECK(ms(f.plan.display) == Approx(16.0 * static_cast<double>(n + 1)).margin(1e-9));
    CHECK(ms(f.plan.wake_up) == Approx(16.0 * static_cast<double>(n + 1) - 11.0 + 5.0 * decay).margin(1e-6));
    CHECK(f.sample.missed == (n < 5));
    CHECK(ms(f.sample.cpu) == Approx(3.0).margin(1e-9));
    CHECK(ms(f.sample.draw) == Approx(2.0).margin(1e-9));
    CHECK(ms(f.sample.gpu) == Approx(4.0).margin(1e-9));
  }
  CHECK(rig.figures["frames_late_to_latch"].get<int64_t>() == 5);
}

TEST_CASE("pacing: a step in GPU time past the period misses, steps the frame period up and back as derived") {
  // 62.5 Hz, C 1 ms, R 1 ms, G 4 ms; from frame 50 G takes 20 ms (more than
  // the 16 ms period), from frame 100 4 ms again; one frame in flight.
  // Before the step the estimates are 1 + 0.8^n, 1 + 0.8^n and 4 - 4 * 0.8^n
  // (from 2, 2 and 0 ms): frame n is done 2 * 0.8^n after its prediction,
  // at most the 2 ms margin (frame 0 exactly at its latch), so nothing
  // misses. Frame
  // 50 + k (k < 50) is planned with k samples of 20: gpu_est = 20 - 16 * 0.8^k
  // (the pre-step residual, 2 * 0.8^50 < 3e-5 ms, is left out), so it is done
  // 16 * 0.8^k after its prediction and misses its latch while
  // 16 * 0.8^k > 2 (margin): k = 0 .. 9, ten frames (16 * 0.8^9 = 2.15,
  // 16 * 0.8^10 = 1.72). The frame period is two refreshes once gpu_est
  // exceeds 16 ms: 0.8^k < 1/4, k >= 7 (frame 57; 0.8^6 = 0.262). After the
  // step back, frame 100 + k has gpu_est = 4 + 16 * 0.8^k, over 16 while
  // 0.8^k > 3/4: k = 0, 1; frame 102 is the first at one refresh again. It
  // is done early, so no miss.
  FrameStagesSpec spec = three_spans(1, 1, 4, 1);
  spec.stages[2].shape.steps = {{50, Time::ms(20)}, {100, Time::ms(4)}};
  Rig rig(spec);
  rig.run(3.0);
  const auto& log = rig.pipeline.app_pacing()->log();
  REQUIRE(log.size() >= 130);
  int misses = 0;
  for (size_t n = 0; n < 130; ++n) {
    INFO("frame " << n);
    const PacedFrame& f = log[n];
    const bool in_step = n >= 50 && n < 100;
    CHECK(f.sample.missed == (n >= 50 && n <= 59));
    misses += f.sample.missed ? 1 : 0;
    CHECK(f.plan.frame_periods == ((n >= 57 && n <= 101) ? 2 : 1));
    if (in_step) {
      const double k = static_cast<double>(n - 50);
      CHECK(ms(f.sample.gpu_done - f.plan.predicted_done) == Approx(16.0 * std::pow(0.8, k)).margin(1e-3));
    }
  }
  CHECK(misses == 10);
  CHECK(rig.figures["frames_late_to_latch"].get<int64_t>() == 10);
}

TEST_CASE("pacing: GPU time stepping from 4 to 9 ms at 90 Hz misses five frames, the period stays one refresh") {
  // 90 Hz (P = 11.111 ms), C 1 ms, R 1 ms, G 4 ms, from frame 200 9 ms, from
  // frame 400 4 ms again; one frame in flight, no compositor. Frame 200 + k
  // is planned with k samples of 9: gpu_est = 9 - 5 * 0.8^k (before the step
  // the estimates sum to the 6 ms of work from the start), so it is done
  // 5 * 0.8^k after its prediction and late to its latch while
  // 5 * 0.8^k > 2 ms: k = 0 .. 4 (5 * 0.8^4 = 2.05, 5 * 0.8^5 = 1.64). No
  // estimate exceeds P, so the frame period stays one refresh; with 11 ms of
  // work and 2 of margin a frame planned when the previous is done (2 ms
  // before its retrace) still fits before the next retrace, 0.11 ms to spare.
  // After the step back frames are done early: none late. Away from the
  // transient (frames 200 .. 219, when a frame planned with a smaller error
  // than its predecessor's finds the next retrace too close) the display
  // times are a refresh apart.
  RigOptions o;
  o.field_period = latsim::des::RationalSeconds::period_of_hz(90);
  FrameStagesSpec spec = three_spans(1, 1, 4, 1);
  spec.stages[2].shape.steps = {{200, Time::ms(9)}, {400, Time::ms(4)}};
  Rig rig(spec, o);
  rig.run(5.0);
  const auto& log = rig.pipeline.app_pacing()->log();
  REQUIRE(log.size() >= 440);
  for (size_t n = 0; n < 440; ++n) {
    INFO("frame " << n);
    CHECK(log[n].sample.missed == (n >= 200 && n <= 204));
    CHECK(log[n].plan.frame_periods == 1);
    if (n >= 200 && n < 400)
      CHECK(ms(log[n].sample.gpu_done - log[n].plan.predicted_done) ==
            Approx(5.0 * std::pow(0.8, static_cast<double>(n - 200))).margin(1e-3));
    if (n > 0 && (n < 200 || n >= 220))
      CHECK(ms(log[n].plan.display - log[n - 1].plan.display) == Approx(1000.0 / 90.0).margin(1e-6));
  }
  CHECK(rig.figures["frames_late_to_latch"].get<int64_t>() == 5);
}

TEST_CASE("pacing: on a light steady workload Monado and just-in-time pacing save period minus work minus margin") {
  // 90 Hz (11.111 ms), C 1 + R 1 + G 2 = 4 ms of work, two frames in flight,
  // no compositor. Started at a retrace V, a frame reads its pose at V and is
  // shown from the next retrace V + P. Paced, it reads its pose when it
  // wakes, work + margin before the retrace it is shown at: motion-to-photon
  // falls by P - 4 - margin (Monado: 2 ms margin, 5.111 ms; just-in-time:
  // 1 ms, 6.111 ms). The tracker sample's age (under 1 ms) differs between
  // the runs by less than 0.5 ms on average.
  RigOptions o;
  o.field_period = latsim::des::RationalSeconds::period_of_hz(90);
  const double period_ms = 1000.0 / 90.0;
  FrameStagesSpec fixed = three_spans(1, 1, 2, 2);
  fixed.pacing.app = AppPolicy::fixed;
  Rig base(fixed, o);
  base.run(2.0);
  CHECK(base.figures["frames_missed"].get<int64_t>() == 0);

  FrameStagesSpec monado = three_spans(1, 1, 2, 2);
  Rig paced(monado, o);
  paced.run(2.0);
  CHECK(paced.figures["frames_missed"].get<int64_t>() == 0);
  CHECK(base.mtp("mean") - paced.mtp("mean") == Approx(period_ms - 4.0 - 2.0).margin(0.5));

  FrameStagesSpec jit = three_spans(1, 1, 2, 2);
  jit.pacing.app = AppPolicy::just_in_time;
  Rig just(jit, o);
  just.run(2.0);
  CHECK(just.figures["frames_missed"].get<int64_t>() == 0);  // the first, woken a period ahead, is early
  CHECK(base.mtp("mean") - just.mtp("mean") == Approx(period_ms - 4.0 - 1.0).margin(0.5));
}
