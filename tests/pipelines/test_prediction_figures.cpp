// The prediction figures and the motion-phase split, against values derived
// by hand; what each image was predicted for, in the ledger.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "latsim/display/raster_timing.hpp"
#include "latsim/scenario/config.hpp"
#include "run_helpers.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using latsim::testing::base_scenario;
using latsim::testing::fig;
using latsim::testing::run;
using Json = nlohmann::json;

namespace {


double mean_of(const Json& out, const char* name) { return fig(out, name).at("mean").get<double>(); }

}  // namespace

TEST_CASE("without prediction the prediction error is the turn over the horizon", "[prediction]") {
  Json s = base_scenario();  // constant 30 deg/s yaw
  s["host"] = {{"prediction", {{"type", "none"}}}};
  const Json out = run(s);
  // Every image shows its sample's pose; at the instant it was predicted for
  // the head has turned by rate x horizon, image by image.
  CHECK(mean_of(out, "prediction_error_deg") == Approx(30.0 * mean_of(out, "prediction_horizon_ms") * 1e-3).epsilon(1e-9));
  CHECK(fig(out, "prediction_error_mm").at("max").get<double>() == 0.0);
}

TEST_CASE("a fixed horizon is the same for every image", "[prediction]") {
  Json s = base_scenario();
  s["host"] = {{"prediction", {{"type", "constant_velocity"}, {"horizon_ms", 10}}}};
  s["probes"] = {{"points_m", {{0, 0, -2}, {0.5, 0, -2}, {-0.5, 0, -2}}}};
  const Json out = run(s);
  CHECK(fig(out, "prediction_horizon_ms").at("min").get<double>() == Approx(10.0).margin(1e-9));
  CHECK(fig(out, "prediction_horizon_ms").at("max").get<double>() == Approx(10.0).margin(1e-9));
  CHECK(fig(out, "prediction_error_deg").at("p50").get<double>() < 1e-9);
  // Instant rendering from the sample taken at a retrace, shown a field
  // later: probes on the middle row are lit one field plus 22 + 240 of 502
  // line periods after measurement, 10 ms of which the prediction covers.
  const double lit_ms = (1.0 + 262.0 / 502.0) * 1e3 / 60.0;
  // (The median: the first image, from one sample, has no velocity yet.)
  CHECK(fig(out, "registration_error_arcmin").at("p50").get<double>() ==
        Approx(30.0 * 60.0 * (lit_ms - 10.0) * 1e-3).epsilon(0.01));
}

TEST_CASE("constant velocity predicts a straight walk exactly", "[prediction]") {
  Json s = base_scenario();
  s["motion"] = {{"type", "walk"}, {"points", {{0, 1.6, 0}, {0, 1.6, -100}}}, {"speed_m_s", 1.0}};
  s["host"] = {{"prediction", {{"type", "none"}}}};
  const Json none = run(s);
  CHECK(mean_of(none, "prediction_error_mm") == Approx(1.0 * mean_of(none, "prediction_horizon_ms")).epsilon(1e-6));
  s["host"]["prediction"]["type"] = "constant_velocity";
  const Json cv = run(s);
  CHECK(fig(cv, "prediction_error_mm").at("p50").get<double>() < 1e-6);
}

TEST_CASE("the ledger records the instant each image was predicted for", "[prediction]") {
  Json s = base_scenario();
  s["pipeline"]["render"]["fixed_ms"] = 4;
  s["host"] = {{"prediction", {{"type", "constant_velocity"}}}};
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "latsim_prediction_ledger";
  std::filesystem::remove_all(dir);
  latsim::run::RunOptions options;
  options.out_dir = dir;
  options.write_ledger = true;
  latsim::run::run_scenario(latsim::scenario::ScenarioDocument::from_json(s, LATSIM_SOURCE_DIR "/scenarios"),
                                  options);
  std::ifstream in(dir / "frames.csv");
  std::string header;
  std::getline(in, header);
  REQUIRE(header.find("predicted_for_ps") != std::string::npos);
  latsim::display::RasterParams rp;
  rp.field_period = latsim::des::RationalSeconds{1, 60};
  const latsim::display::RasterTiming timing(rp);
  int rows = 0;
  for (std::string line; std::getline(in, line); ++rows) {
    std::stringstream cells(line);
    std::vector<int64_t> v;
    for (std::string cell; std::getline(cells, cell, ',');) v.push_back(std::stoll(cell));
    // frame,eye,field,sample,measured_ps,host_received_ps,render_start_ps,render_end_ps,predicted_for_ps,...
    const int64_t field = v[2], predicted_for = v[8];
    // Rendered right after a retrace in 4 ms, shown at the next one: the
    // host predicted for the middle line of the field the image is shown in.
    CHECK(predicted_for == timing.line_time(field, timing.lines_per_field() / 2).ticks());
  }
  CHECK(rows > 100);
  std::filesystem::remove_all(dir);
}

TEST_CASE("motion phases split a sinusoidal yaw as its speed crosses the threshold", "[prediction][motion_phase]") {
  // Yaw 30 sin(2 pi 0.5 t) degrees: speed 94.25 |cos(pi t)| deg/s, above
  // 40 deg/s while |cos| > 40 / 94.25, i.e. a fraction (2/pi) acos(0.4244) =
  // 0.7210 of the time. Each second holds one start and one stop, so with a
  // 100 ms window onset and stop take 0.1 each; steady 0.6210, still 0.1790.
  Json s = base_scenario();
  s["duration_s"] = 20;
  s["motion"] = {{"type", "sinusoid"}, {"yaw_amplitude_deg", 30}, {"yaw_frequency_hz", 0.5}, {"position_m", {0, 1.6, 0}}};
  s["host"] = {{"prediction", {{"type", "constant_velocity"}}}};
  s["motion_phases"] = {{"threshold_deg_s", 40}, {"window_ms", 100}, {"step_ms", 1}};
  // Probes all around at eye level, so that every field has some in view.
  Json points = Json::array();
  for (int i = 0; i < 72; ++i) points.push_back({-2.0 * std::sin(units::deg_to_rad(i * 5.0)), 1.6, -2.0 * std::cos(units::deg_to_rad(i * 5.0))});
  s["probes"] = {{"points_m", points}};
  const Json out = run(s);
  const double total = static_cast<double>(fig(out, "registration_error_arcmin").at("count").get<int64_t>());
  auto share = [&](const char* phase) {
    return static_cast<double>(fig(out, (std::string("registration_error_arcmin_") + phase).c_str()).at("count").get<int64_t>()) /
           total;
  };
  const double moving = 2.0 / units::kPi * std::acos(40.0 / (30.0 * units::kPi));
  CHECK(share("onset") == Approx(0.1).margin(0.01));
  CHECK(share("stop") == Approx(0.1).margin(0.01));
  CHECK(share("steady") == Approx(moving - 0.1).margin(0.015));
  CHECK(share("still") == Approx(1.0 - moving - 0.1).margin(0.015));
  // Constant velocity misses by the angular acceleration, largest where the
  // head turns round (slow, so mostly still, and at the start and stop of
  // each swing) and nil at full speed.
  CHECK(mean_of(out, "prediction_error_deg_onset") > mean_of(out, "prediction_error_deg_steady"));
  CHECK(mean_of(out, "prediction_error_deg_still") > mean_of(out, "prediction_error_deg_steady"));
}

TEST_CASE("bad prediction settings name their JSON pointer", "[prediction]") {
  Json s = base_scenario();
  s["host"] = {{"prediction", {{"type", "linear"}}}};
  try {
    run(s);
    FAIL("an unknown predictor was accepted");
  } catch (const latsim::scenario::ScenarioError& e) {
    CHECK(std::string(e.what()).find("/host/prediction/type") != std::string::npos);
  }
  s["host"] = {{"prediction", {{"type", "kalman"}, {"angular_accel_noise_deg_s2_rthz", 0}}}};
  CHECK_THROWS_AS(run(s), latsim::scenario::ScenarioError);
  s["host"] = {{"prediction", {{"type", "none"}, {"horizon_ms", -1}}}};
  CHECK_THROWS_AS(run(s), latsim::scenario::ScenarioError);
}
