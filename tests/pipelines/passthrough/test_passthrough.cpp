// The passthrough pipeline on hand-derivable chains: a global-shutter camera
// phase-locked to the display, the same with a rolling shutter, a compositor
// that runs as each frame arrives, a free-running camera at fixed phases and
// averaged over its phase, and the rig filming a moving object through it.
//
// Throughout: a 100 Hz progressive display (10 ms fields, phase 0), 640 x
// 480 with 20 blank lines and no horizontal blanking: 500 lines of 0.02 ms,
// 640 pixel times of 31.25 ns each. The point is the centre: active line 240,
// column 320, written (20 + 240) x 0.02 + 320 x 31.25e-6 = 5.21 ms after
// each retrace; without persistence its photons are that instant. The
// camera has 1000 rows read in 2 us each (2 ms a frame) and exposes 2 ms;
// the ISP takes 1.5 ms a frame; the compositor 1 ms of re-projection and
// 0.5 ms of composition.
#include <catch2/catch.hpp>

#include "run_helpers.hpp"

using latsim::testing::fig;
using latsim::testing::run;
using Json = nlohmann::json;

namespace {

constexpr double kScanoutMs = 5.21;  // retrace to the centre pixel's photons
constexpr double kTol = 1e-6;

Json passthrough(const Json& camera, const Json& compositor) {
  return {{"duration_s", 1},
          {"seed", 3},
          {"motion", {{"type", "constant"}, {"axis", {0, 1, 0}}, {"rate_deg_s", 30}}},
          {"tracker", {{"rate_hz", 1000}, {"phase_ms", 0}, {"internal_delay_ms", 0}}},
          {"transport", {{"type", "direct"}}},
          {"display",
           {{"refresh_hz", 100}, {"width_px", 640}, {"height_px", 480}, {"vblank_lines", 20}, {"hblank_px", 0},
            {"hfov_deg", 60}, {"phase_ms", 0}, {"scanout", "line"}}},
          {"pipeline",
           {{"type", "passthrough"},
            {"camera", camera},
            {"isp", {{"fixed_ms", 1.5}}},
            {"compositor", compositor}}}};
}

Json camera(const char* shutter, const Json& sync) {
  Json c = {{"height_px", 1000}, {"exposure_ms", 2}, {"row_readout_us", 2}, {"shutter", shutter}};
  c.update(sync);
  return c;
}

const Json kLocked = {{"sync", "display"}, {"sync_offset_ms", 1}};
const Json kBeforeRetrace = {{"start", "before_retrace"}, {"lead_ms", 2}, {"reprojection_ms", 1}, {"composition_ms", 0.5}};

double stat(const Json& out, const char* name, const char* s) { return fig(out, name).at(s).get<double>(); }

}  // namespace

TEST_CASE("passthrough: a global-shutter camera phase-locked to the display gives the derived photon-to-photon") {
  // Frame k opens 1 ms after retrace k (10k + 1 ms), every row exposed to
  // 10k + 3: exposure middle 10k + 2. The rows are read out by 10k + 3 + 2 =
  // 10k + 5; the ISP ends at 10k + 6.5. The compositor for retrace k + 1
  // starts 2 ms before it (10k + 8), takes frame k, ends at 10k + 9.5; frame
  // k is swapped in at 10(k + 1) and the centre lit at 10(k + 1) + 5.21:
  // photon-to-photon 10 + 5.21 - 2 = 13.21 ms at every refresh. Stages:
  // camera 3 (2 -> 5), ISP 1.5, queue 1.5 (6.5 -> 8), re-projection 1.5,
  // display wait 0.5, scanout 5.21; they add up to 13.21.
  const Json out = run(passthrough(camera("global", kLocked), kBeforeRetrace));
  const double p2p = 10.0 + kScanoutMs - 2.0;
  CHECK(stat(out, "photon_to_photon_ms", "min") == Approx(p2p).margin(kTol));
  CHECK(stat(out, "photon_to_photon_ms", "max") == Approx(p2p).margin(kTol));
  CHECK(stat(out, "camera_ms", "mean") == Approx(3.0).margin(kTol));
  CHECK(stat(out, "isp_ms", "mean") == Approx(1.5).margin(kTol));
  CHECK(stat(out, "reprojection_queue_ms", "mean") == Approx(1.5).margin(kTol));
  CHECK(stat(out, "reprojection_ms", "mean") == Approx(1.5).margin(kTol));
  CHECK(stat(out, "display_wait_ms", "mean") == Approx(0.5).margin(kTol));
  CHECK(stat(out, "scanout_ms", "mean") == Approx(kScanoutMs).margin(kTol));
  // Frames read out by 1 s: 10k + 5 <= 1000, k = 0..99; frame k is shown at
  // retrace k + 1, and the run's retraces are 0..99: frames 0..98, once each.
  const Json& f = out.at("figures");
  CHECK(f.at("camera_frames").get<int64_t>() == 100);
  CHECK(f.at("camera_frames_shown").get<int64_t>() == 99);
  CHECK(fig(out, "photon_to_photon_ms").at("count").get<int64_t>() == 99);
  CHECK(f.at("camera_frames_dropped").get<int64_t>() == 0);
  CHECK(f.at("camera_frames_repeated").get<int64_t>() == 0);
  CHECK(f.at("warps_late").get<int64_t>() == 0);
  // The compositor's pose: the newest 1 kHz sample at its start (10k + 8,
  // or the one a millisecond before when the sample of that very instant
  // comes after it), unpredicted; the first active line is lit 0.4 ms into
  // the field: the youngest pose on the display is 2.4 to 2.401 ms old.
  CHECK(stat(out, "motion_to_photon_ms", "min") >= 2.4 - kTol);
  CHECK(stat(out, "motion_to_photon_ms", "min") <= 2.401 + kTol);
}

TEST_CASE("passthrough: on a globally flashed panel the photons wait for the whole field") {
  // A global flash of 2 ms with no response time lights every pixel of a
  // field once its last line is written: 20 blank and 480 active lines fill
  // the whole 10 ms field, so the flash is [10, 12] ms after the retrace
  // that swapped the frame in, its middle 11 ms: photon-to-photon 10 + 11 -
  // 2 = 19 ms, of which scanout 11.
  Json s = passthrough(camera("global", kLocked), kBeforeRetrace);
  s["display"]["persistence"] = {{"type", "global"}, {"lit_ms", 2}, {"response_ms", 0}};
  const Json out = run(s);
  CHECK(stat(out, "photon_to_photon_ms", "mean") == Approx(19.0).margin(kTol));
  CHECK(stat(out, "scanout_ms", "mean") == Approx(11.0).margin(kTol));
}

TEST_CASE("passthrough: a rolling shutter sees the point's row later by its row offset") {
  // Row 500 (the centre of 1000 rows) opens 500 x 2 us = 1 ms after row 0:
  // exposed 10k + 2 to 10k + 4, middle 10k + 3. The last row still closes at
  // 10k + 1 + 1.998 + 2 and is read by 10k + 5: everything after the camera
  // is unchanged, and photon-to-photon is 1 ms shorter: 12.21 ms.
  const Json out = run(passthrough(camera("rolling", kLocked), kBeforeRetrace));
  CHECK(stat(out, "photon_to_photon_ms", "mean") == Approx(10.0 + kScanoutMs - 3.0).margin(kTol));
  CHECK(stat(out, "camera_ms", "mean") == Approx(2.0).margin(kTol));
  CHECK(stat(out, "isp_ms", "mean") == Approx(1.5).margin(kTol));
}

TEST_CASE("passthrough: a compositor that runs on each new frame waits at the display instead") {
  // It starts at the ISP's end (10k + 6.5), ends at 10k + 8, for the first
  // retrace after that (10(k + 1)): photon-to-photon unchanged, no queue, a
  // display wait of 2 ms.
  const Json out = run(passthrough(camera("global", kLocked), {{"start", "on_frame"}, {"reprojection_ms", 1},
                                                               {"composition_ms", 0.5}}));
  CHECK(stat(out, "photon_to_photon_ms", "mean") == Approx(10.0 + kScanoutMs - 2.0).margin(kTol));
  CHECK(stat(out, "reprojection_queue_ms", "max") == Approx(0.0).margin(kTol));
  CHECK(stat(out, "display_wait_ms", "mean") == Approx(2.0).margin(kTol));
}

TEST_CASE("passthrough: a free-running camera adds half a display period on average over its phase") {
  // A 100 Hz camera of its own with phase p in [0, 10): frame k opens at
  // p + 10k, its exposure middle p + 10k + 1, read out by p + 10k + 4, the
  // ISP done by p + 10k + 5.5. The compositor at 10m + 8 takes the newest
  // processed frame: frame m when p + 5.5 <= 8 (p <= 2.5), else frame m - 1.
  // Photon-to-photon: 10(m + 1) + 5.21 - (p + 10k + 1) = 14.21 - p for
  // p < 2.5, 24.21 - p above (at 2.5 exactly the compositor, scheduled
  // first, runs before the ISP's end of the same instant). Its mean over p: (14.21 x 2.5 - 2.5²/2 +
  // 24.21 x 7.5 - (10² - 2.5²)/2) / 10 = 16.71 ms = 11.71 (the locked best,
  // p = 2.5) + 5, half the 10 ms period.
  auto at_phase = [](double phase_ms) {
    Json s = passthrough(camera("global", {{"sync", "free"}, {"fps", 100}, {"phase_ms", phase_ms}}), kBeforeRetrace);
    s["duration_s"] = 0.2;
    return stat(run(s), "photon_to_photon_ms", "mean");
  };
  CHECK(at_phase(1.0) == Approx(14.21 - 1.0).margin(kTol));
  CHECK(at_phase(2.0) == Approx(14.21 - 2.0).margin(kTol));
  CHECK(at_phase(3.0) == Approx(24.21 - 3.0).margin(kTol));
  // The midpoint rule over cells of 0.5 ms is exact for a function linear
  // on each cell (its jump at 2.5 is a cell boundary).
  double sum = 0.0;
  for (int i = 0; i < 20; ++i) sum += at_phase(0.25 + 0.5 * i);
  CHECK(sum / 20.0 == Approx(16.71).margin(1e-6));
}

TEST_CASE("passthrough: a drifting free-running camera sweeps its phase and averages to the same") {
  // 1000 ppm fast: frame k opens at 10k / 1.001 ms, 0.00999k ms earlier on
  // the display's grid each frame, so over the 1000 refreshes of 10 s the
  // phase sweeps 9.99 ms, almost once through a period, at an even pace:
  // the mean is the phase average derived above, 16.71 ms, to within what
  // the last 0.01 ms of the sweep and the first refreshes (before the first
  // frame is shown) move it (well under 0.05 ms).
  Json s = passthrough(
      camera("global", {{"sync", "free"}, {"fps", 100}, {"phase_ms", 9.995}, {"rate_error_ppm", 1000}}),
      kBeforeRetrace);
  s["duration_s"] = 10;
  const Json out = run(s);
  CHECK(stat(out, "photon_to_photon_ms", "mean") == Approx(16.71).margin(0.05));
  CHECK(stat(out, "photon_to_photon_ms", "min") == Approx(11.71).margin(0.02));
  CHECK(stat(out, "photon_to_photon_ms", "max") == Approx(21.71).margin(0.02));
}

TEST_CASE("passthrough: a camera at half the refresh rate is re-projected twice per frame") {
  // Frame k now opens 1 ms after retrace 2k: shown at retrace 2k + 1 as
  // before (13.21 ms) and re-projected again for retrace 2k + 2 (23.21 ms):
  // the mean is 18.21 ms, and every other composition repeats a frame.
  Json cam = camera("global", kLocked);
  cam["refreshes_per_frame"] = 2;
  const Json out = run(passthrough(cam, kBeforeRetrace));
  CHECK(stat(out, "photon_to_photon_ms", "min") == Approx(13.21).margin(kTol));
  CHECK(stat(out, "photon_to_photon_ms", "max") == Approx(23.21).margin(kTol));
  // Refreshes 1..99 show frames: 50 first showings (odd refreshes), 49
  // repeats; the compositor also re-projects frame 49 for retrace 100 (at
  // 998 ms), which the 1 s run ends at: 50 repeated compositions.
  CHECK(stat(out, "photon_to_photon_ms", "mean") == Approx((50 * 13.21 + 49 * 23.21) / 99.0).margin(kTol));
  CHECK(out.at("figures").at("camera_frames_repeated").get<int64_t>() == 50);
  CHECK(stat(out, "scanout_ms", "mean") == Approx(kScanoutMs).margin(kTol));
}

TEST_CASE("passthrough: the rig filming a moving object through the headset measures photon-to-photon") {
  // A full-persistence panel holds the centre's value for the whole field
  // from its write: lit [w, w + 10 ms], middle w + 5, so photon-to-photon
  // is 18.21 ms. The rig (1000 fps, 1 ms exposures) films an object making
  // 30 degree minimum-jerk turns and its image: the trajectory shift is the
  // delay of the shown trajectory, the same 18.21 ms within the rig's
  // sampling of the held image (a camera frame, 1 ms).
  Json s = passthrough(camera("global", kLocked), kBeforeRetrace);
  s["duration_s"] = 4;
  s["display"]["persistence"] = {{"type", "full"}};
  s["pipeline"]["object"] = {{"type", "minimum_jerk"}, {"amplitude_deg", 30}, {"duration_s", 0.4}, {"rest_s", 0.4}};
  s["pipeline"]["rig"] = {{"fps", 1000}, {"phase_ms", 0.25}, {"exposure_ms", 1}};
  const Json out = run(s);
  const double p2p = 10.0 + kScanoutMs + 5.0 - 2.0;
  CHECK(stat(out, "photon_to_photon_ms", "mean") == Approx(p2p).margin(kTol));
  CHECK(out.at("figures").at("photon_to_photon_rig_movements").get<int64_t>() >= 4);
  CHECK(stat(out, "photon_to_photon_rig_shift_ms", "mean") == Approx(p2p).margin(1.0));
}

TEST_CASE("passthrough: bad camera settings are refused at their pointer") {
  Json s = passthrough(camera("global", kLocked), kBeforeRetrace);
  s["pipeline"]["camera"]["row_readout_us"] = 20;  // 1000 rows x 20 us = 20 ms: more than a 10 ms frame
  CHECK_THROWS_WITH(run(s), Catch::Contains("/pipeline/camera") && Catch::Contains("readout"));
  Json t = passthrough(camera("global", kLocked), kBeforeRetrace);
  t["pipeline"]["rig"] = {{"fps", 1000}};
  CHECK_THROWS_WITH(run(t), Catch::Contains("/pipeline/rig"));
  // The rig films /pipeline/object: asking for the controller names that, not /controller.
  t["pipeline"]["object"] = {{"type", "still"}};
  t["pipeline"]["rig"]["object"] = "controller";
  CHECK_THROWS_WITH(run(t), Catch::Contains("/pipeline/rig/object") &&
                                Catch::Contains("films the real object of /pipeline/object") &&
                                !Catch::Contains("/controller"));
}
