// The shipped scenarios of scenarios/modern run through the runner: the
// eleven reference configurations against the ranges derived from the
// article's diagrams (docs/modern.md), the overload, the persistence twins.
//
// The reference display has 480 lines of 16/480 ms, so the bottom line is
// lit 15.967 ms after the top one; the tracker's samples are at most one
// period old when read (and, clocks being free to run at any phase, of any
// age in [0, P) that stays the same through a run, all periods being whole
// milliseconds): min in [D_min, D_min + P), max in [D_max - 1/30, D_max + P).
#include <catch2/catch.hpp>

#include <string>

#include "scenario_helpers.hpp"

using latsim::testing::run_shipped;

namespace {

struct Reference {
  const char* file;
  double min_ms;  ///< the diagram's range by hand: pose read to top line lit
  double tracker_period_ms;
};

// Each range, derived in docs/modern.md from the stage durations read off the diagram:
const Reference kReferences[] = {
    {"vsync", 16.0, 1.0},                      // read at V_k, shown from V_{k+1}
    {"unsynchronized", 4.0, 1.0},              // shown as completed, 4 ms after the read, for 4 ms
    {"cpu_gpu_pipelined", 32.0, 1.0},          // G waits for the swap at V_{k+1}, shown from V_{k+2}
    {"split_threads", 48.0, 1.0},              // CPU1 at V_k, CPU2 at V_{k+1}, G at V_{k+2}, shown V_{k+3}
    {"minimal_gpu_buffering", 32.0, 1.0},      // G streams R at V_{k+1} + 1, shown from V_{k+2}
    {"alternate_frame_rendering", 48.0, 1.0},  // G (24 ms) ends V_{k+2} + 9, shown from V_{k+3}
    {"late_frame_scheduling", 17.0, 1.0},      // I at V_{k+1} - 1, shown from V_{k+2} (article: 18)
    {"view_bypass", 16.0, 1.0},                // view read again at V_{k+1}, shown from V_{k+2}
    {"late_view_bypass", 12.0, 1.0},           // view read at V_{k+2} - 12, shown from V_{k+2}
    {"timewarp", 2.0, 1.0},                    // warp reads at V - 2 (with depth), shown from V
    {"tiler_view_bypass", 16.0, 1.0},          // view written at V_{k+2}, shown from V_{k+3}
};

}  // namespace

TEST_CASE("modern scenarios: each reference configuration's latency range is the diagram's") {
  for (const Reference& r : kReferences) {
    INFO(r.file);
    const auto f = run_shipped(std::string("modern/") + r.file + ".json", {"/duration_s=2"});
    const auto& mtp = f.at("motion_to_photon_ms");
    // Unsynchronized frames replace each other every 4 ms, so its maximum is
    // 4 ms after its minimum; elsewhere a frame is held the 16 ms of scanout.
    const double span = std::string(r.file) == "unsynchronized" ? 4.0 : 16.0;
    CHECK(mtp.at("min").get<double>() >= r.min_ms - 1e-6);
    CHECK(mtp.at("min").get<double>() < r.min_ms + r.tracker_period_ms);
    CHECK(mtp.at("max").get<double>() >= r.min_ms + span - 1.0 / 30.0 - 1e-6);
    CHECK(mtp.at("max").get<double>() < r.min_ms + span + r.tracker_period_ms);
    CHECK(f.at("frames_missed").get<int64_t>() == 0);
  }
}

TEST_CASE("modern scenarios: on the article's clocks each range is the diagram's exactly, and a sample's age moves it") {
  // base.json puts the 1000 Hz samples and the retraces on whole
  // milliseconds from t = 0, the diagrams' assumption: every read finds a
  // sample taken that instant (age 0), so min = D_min and max = D_max - 16/480.
  for (const Reference& r : kReferences) {
    INFO(r.file);
    const auto f = run_shipped(std::string("modern/") + r.file + ".json", {"/duration_s=2"});
    const double span = std::string(r.file) == "unsynchronized" ? 4.0 : 16.0;
    CHECK(f.at("motion_to_photon_ms").at("min").get<double>() == Approx(r.min_ms).margin(1e-6));
    CHECK(f.at("motion_to_photon_ms").at("max").get<double>() == Approx(r.min_ms + span - 1.0 / 30.0).margin(1e-6));
  }
  // Samples taken 0.4 ms after each whole millisecond: a read on a whole
  // millisecond finds one 0.6 ms old, and the whole range moves by 0.6 ms
  // (unsynchronized: the article's 5 - 8 would need 1 ms, a whole period).
  const auto late = run_shipped("modern/unsynchronized.json", {"/duration_s=2", "/tracker/phase_ms=0.4"});
  CHECK(late.at("motion_to_photon_ms").at("min").get<double>() == Approx(4.6).margin(1e-6));
  CHECK(late.at("motion_to_photon_ms").at("max").get<double>() == Approx(8.6 - 1.0 / 30.0).margin(1e-6));
}

TEST_CASE("modern scenarios: continuous time warp is 1 ms plus its 2 ms strip plus a 500 Hz sample's age") {
  // Strip s is warped in the millisecond before its first line, from a sample
  // up to 2 ms old: min in [1, 3), max in [1 + 2 - 1/30, 3 + 2).
  const auto f = run_shipped("modern/continuous_timewarp.json", {"/duration_s=2"});
  const auto& mtp = f.at("motion_to_photon_ms");
  CHECK(mtp.at("min").get<double>() >= 1.0 - 1e-6);
  CHECK(mtp.at("min").get<double>() < 3.0);
  CHECK(mtp.at("max").get<double>() >= 3.0 - 1.0 / 30.0 - 1e-6);
  CHECK(mtp.at("max").get<double>() < 5.0);
  // A 2 ms strip: the spread within a run is one strip (the sample age is the same for every strip).
  CHECK(mtp.at("max").get<double>() - mtp.at("min").get<double>() == Approx(2.0 - 1.0 / 30.0).margin(1e-6));
  CHECK(f.at("warps_late").get<int64_t>() == 0);
}

TEST_CASE("modern scenarios: under overload the compositor serves every refresh and re-warps old frames") {
  // 90 Hz, G of 16.667 ms = 1.5 refreshes, and the compositor takes 1 ms of
  // GPU per refresh: the application completes a frame every 16.667 + 1.5 ms,
  // 55 per second, so 35 of every 90 refreshes re-warp an old frame. Every
  // refresh after the first image is warped, none late. Walking at 1.4 m/s
  // with a rotation-only warp, the position shown is as old as the frame: a
  // re-warped one is a refresh (11.1 ms, 15.6 mm) older than when new, on
  // average less than that since the frames that are re-warped are the ones
  // that arrived early.
  const auto f = run_shipped("modern/timewarp_overload.json", {"/duration_s=5"});
  const int64_t refreshes = f.at("fields").get<int64_t>();
  CHECK(f.at("warps").get<int64_t>() + f.at("refreshes_without_image").get<int64_t>() == refreshes);
  CHECK(f.at("warps_late").get<int64_t>() == 0);
  CHECK(f.at("application_frame_rate_hz").get<double>() == Approx(1000.0 / (16.667 + 1.5)).margin(1.0));
  CHECK(f.at("frames_missed").get<double>() / refreshes == Approx(35.0 / 90.0).margin(0.03));
  const auto& by = f.at("residual_by_rewarps");
  REQUIRE(by.size() >= 2);
  CHECK(by.at(0).at("rewarps") == 0);
  CHECK(by.at(1).at("rewarps") == 1);
  CHECK(by.at(1).at("position_mm_mean").get<double>() > by.at(0).at("position_mm_mean").get<double>() + 5.0);
}

TEST_CASE("modern scenarios: a walk that turns its corners at 90 deg/s leaves no 90 degree spike behind the warp") {
  // The square's corners are 90 degree turns, centred on the corner, at the
  // default 90 deg/s. The warp reads a sample at most P = 1 ms old, starts at
  // most its 1 ms cost plus one 0.5 ms preemption slice before the retrace,
  // and the field's last line is lit (1199/1200) x 11.11 ms after it: the
  // orientation shown is at most 13.61 ms old, so it is off by at most
  // 90 deg/s x 13.61 ms = 1.225 deg. Turned at once, the corner puts the
  // whole 90 degrees between a sample before it and a photon after it.
  const double bound_deg = 90.0 * (1.0 + 1.0 + 0.5 + 1000.0 / 90.0) / 1000.0;
  const auto turned = run_shipped("modern/timewarp_overload.json", {"/duration_s=5"});
  CHECK(turned.at("residual_orientation_error_deg").at("max").get<double>() <= bound_deg);
  CHECK(turned.at("residual_orientation_error_deg").at("max").get<double>() > 0.5 * bound_deg);  // the turn is seen
  const auto instant = run_shipped("modern/timewarp_overload.json", {"/duration_s=5", "/motion/turn_rate_deg_s=0"});
  CHECK(instant.at("residual_orientation_error_deg").at("max").get<double>() == Approx(90.0).margin(1e-6));
}

TEST_CASE("modern scenarios: the low-persistence HMD smears far less than its full-persistence twin") {
  // 120 deg/s: a 2 ms flash smears 0.24 deg = 14.4 arcmin, a frame held for
  // 11.1 ms 1.333 deg = 80 arcmin.
  const auto low = run_shipped("modern/low_persistence_90hz.json", {"/duration_s=1"});
  const auto full = run_shipped("modern/full_persistence_90hz.json", {"/duration_s=1"});
  CHECK(low.at("smear_arcmin").at("mean").get<double>() == Approx(14.4).epsilon(1e-6));
  CHECK(full.at("smear_arcmin").at("mean").get<double>() == Approx(80.0).epsilon(1e-6));
  // Motion-to-photon moves to the middle of the lit interval: rolling lights
  // a row 0.1 + 1 ms after it is written, full persistence 0.05 + 5.56 ms.
  const double shift = full.at("motion_to_photon_ms").at("min").get<double>() -
                       low.at("motion_to_photon_ms").at("min").get<double>();
  CHECK(shift == Approx((0.05 + 500.0 / 90.0) - 1.1).margin(1e-3));
}

TEST_CASE("modern scenarios: the staged vsync configuration agrees with the double-buffered pipeline") {
  // A second, independent model of the same system: double_buffer renders a
  // frame from the newest pose at each retrace in 4 ms (I + S + R + G) and
  // swaps it in at the next one. Every figure of the latency distribution
  // must be the same.
  const auto staged = run_shipped("modern/vsync.json", {"/duration_s=2"});
  const auto classic = run_shipped(
      "modern/vsync.json",
      {"/duration_s=2", R"(/pipeline={"type": "double_buffer", "render": {"fixed_ms": 4}})"});
  for (const char* figure : {"motion_to_photon_ms", "image_age_ms", "registration_error_arcmin"})
    for (const char* stat : {"count", "min", "mean", "max"}) {
      INFO(figure << "." << stat);
      CHECK(staged.at(figure).at(stat).get<double>() == Approx(classic.at(figure).at(stat).get<double>()).epsilon(1e-12));
    }
}

TEST_CASE("pixel fidelity on a continuous time warp: per-pixel latency, residual errors as at line fidelity", "[modern]") {
  // 62.5 Hz, 480 lines of 640 pixels, no blanking: a line lasts 16/480 ms and
  // a pixel 1/640 of that. Every strip's pose is uniform along a line, so the
  // mean over pixels is the line's latency plus the mean pixel offset,
  // (640 - 1)/2 pixel periods; the residual errors are judged once per line
  // at its first pixel, the instant line fidelity uses, so they are equal.
  // The run ends (1 s: mid-field) at the first pixel of a line, which line
  // fidelity counts whole and pixel fidelity as that one pixel: 639 pixels
  // fewer, each at most 4 ms (the figure's maximum), which moves the mean by
  // at most 639 * 4 / 18.6e6 = 1.4e-4 ms.
  const auto line = run_shipped("modern/continuous_timewarp.json", {"/duration_s=1", "/display/scanout=\"line\""});
  const auto pixel = run_shipped("modern/continuous_timewarp.json", {"/duration_s=1", "/display/scanout=\"pixel\""});
  const double pixel_ms = 16.0 / 480.0 / 640.0;
  const double offset_ms = (640 - 1) / 2.0 * pixel_ms;
  CHECK(pixel["rotation_latency_ms"]["mean"].get<double>() - line["rotation_latency_ms"]["mean"].get<double>() ==
        Approx(offset_ms).margin(1.4e-4));
  CHECK(pixel["rotation_latency_ms"]["count"].get<double>() ==
        640 * line["rotation_latency_ms"]["count"].get<double>() - 639);
  CHECK(pixel["residual_orientation_error_deg"] == line["residual_orientation_error_deg"]);
  CHECK(pixel["residual_position_error_mm"] == line["residual_position_error_mm"]);
  CHECK(pixel["residual_by_rewarps"] == line["residual_by_rewarps"]);
}
