// Apparent latency and the camera rig in whole runs, against values derived
// by hand from the scenario's timing.
#include <catch2/catch.hpp>

#include <cmath>

#include "run_helpers.hpp"

using latsim::testing::base_scenario;
using latsim::testing::fig;
using latsim::testing::run;
using Json = nlohmann::json;

namespace {

double figure(const Json& out, const char* name, const char* stat) { return fig(out, name).at(stat).get<double>(); }

}  // namespace

TEST_CASE("apparent latency of a pure delay is that delay", "[apparent_latency]") {
  // base_scenario: 60 Hz display (22 blanking + 480 active lines, no
  // persistence: impulses), tracker at 60 Hz in phase with it, instant
  // rendering from the sample measured at the retrace, shown a field later.
  // The centre pixel (line 240) is lit (1 + (22 + 240) / 502) fields after
  // the measurement of the pose it shows: a constant delay.
  Json s = base_scenario();
  s["motion"]["rate_deg_s"] = 60;  // above the 40 deg/s of the default motion phases: steady motion
  s["apparent_latency"] = Json::object();
  const Json out = run(s);
  const double d_ms = (1.0 + 262.0 / 502.0) * 1000.0 / 60.0;  // 25.365 ms
  CHECK(figure(out, "apparent_latency_ms", "min") == Approx(d_ms).margin(1e-3));
  CHECK(figure(out, "apparent_latency_ms", "max") == Approx(d_ms).margin(1e-3));
  // Constant motion from time zero: every window is steady motion.
  CHECK(figure(out, "apparent_latency_ms_steady", "count") == figure(out, "apparent_latency_ms", "count"));
  // Without apparent_latency in the scenario there is no such figure.
  CHECK_FALSE(run(base_scenario()).at("figures").contains("apparent_latency_ms"));
}

TEST_CASE("without prediction apparent latency is motion-to-photon in steady motion", "[apparent_latency]") {
  // A 1000 Hz tracker and display phases drawn per run: each refresh shows a
  // pose of another age, all within one tracker period (1 ms) of each other.
  // At constant speed a window's least-squares shift is the mean age at the
  // centre pixel over the window, and motion_to_photon_ms's mean over all
  // lines is the centre line's within half a line: the two means differ by
  // less than the 1 ms spread of the ages.
  Json s = base_scenario();
  s["duration_s"] = 5;
  s["motion"]["rate_deg_s"] = 60;
  s["tracker"] = {{"rate_hz", 1000}};
  s["display"].erase("phase_ms");
  s["apparent_latency"] = Json::object();
  const Json out = run(s);
  CHECK(figure(out, "apparent_latency_ms_steady", "mean") ==
        Approx(figure(out, "motion_to_photon_ms", "mean")).margin(1.0));
}

TEST_CASE("a perfect predictor under constant velocity shows no apparent latency", "[apparent_latency]") {
  // Constant velocity extrapolates a constant turn exactly, to the middle
  // line's photon time: the centre pixel shows the truth (half a line at most).
  Json s = base_scenario();
  s["host"] = {{"prediction", {{"type", "constant_velocity"}}}};
  s["apparent_latency"] = Json::object();
  const Json out = run(s);
  CHECK(figure(out, "apparent_latency_ms", "p50") == Approx(0.0).margin(0.05));
}

TEST_CASE("prediction lags at the onset of minimum-jerk movements and catches up", "[apparent_latency]") {
  Json s = base_scenario();
  s["duration_s"] = 6;
  s["motion"] = {{"type", "minimum_jerk"}, {"amplitude_deg", 40}, {"duration_s", 0.5}, {"rest_s", 0.5}};
  s["tracker"] = {{"rate_hz", 1000}, {"phase_ms", 0}};
  s["apparent_latency"] = Json::object();
  const Json none = run(s);
  s["host"] = {{"prediction", {{"type", "constant_velocity"}}}};
  const Json cv = run(s);
  // No prediction: about the same lag at onset and in steady motion.
  CHECK(figure(none, "apparent_latency_ms_onset", "mean") ==
        Approx(figure(none, "apparent_latency_ms_steady", "mean")).margin(3.0));
  // Prediction: much less lag in steady motion, more at onset than steady.
  CHECK(figure(cv, "apparent_latency_ms_steady", "mean") < 0.5 * figure(none, "apparent_latency_ms_steady", "mean"));
  CHECK(figure(cv, "apparent_latency_ms_onset", "mean") > figure(cv, "apparent_latency_ms_steady", "mean") + 2.0);
  CHECK(figure(cv, "prediction_catch_up_ms", "count") >= 4);
  CHECK(figure(cv, "prediction_catch_up_ms", "mean") > figure(none, "prediction_catch_up_ms", "mean"));
}

TEST_CASE("the camera rig films a run", "[camera_rig]") {
  // Pure delay as above (25.365 ms at the centre pixel, one flash per 60 Hz
  // refresh): the display's movement is seen at the first flash past the
  // threshold, up to a refresh after the object's, so frame counting is
  // within a refresh plus a camera frame of the delay.
  Json s = base_scenario();
  s["duration_s"] = 6;
  s["motion"] = {{"type", "minimum_jerk"}, {"amplitude_deg", 30}, {"duration_s", 0.5}, {"rest_s", 0.5}};
  s["measurement"] = {{"fps", 240}};
  const Json out = run(s);
  const double d_ms = (1.0 + 262.0 / 502.0) * 1000.0 / 60.0;
  CHECK(fig(out, "measurement_movements").get<int64_t>() >= 5);
  CHECK(fig(out, "measurement_resolution_ms").get<double>() == Approx(1000.0 / 240 / 2));
  CHECK(figure(out, "measured_latency_ms", "mean") == Approx(d_ms).margin(1000.0 / 60 + 1000.0 / 240));
  // The trajectory shift reads each flash (at p, inside a frame's exposure
  // [t, t + T]) against the object's mean over that exposure, ≈ its angle at
  // t + T/2: every lit frame says d + (t + T/2 − p), within half a frame of d.
  CHECK(figure(out, "measured_latency_shift_ms", "mean") == Approx(d_ms).margin(1000.0 / 240 / 2));
  // The camera's phase is drawn per run and written back into the resolved scenario.
  CHECK(out.at("scenario").at("measurement").contains("phase_ms"));
}
