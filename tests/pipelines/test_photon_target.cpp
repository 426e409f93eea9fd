// Prediction aims at the photon: an exact predictor (constant velocity on a
// constant-rate yaw) leaves registration error at the level of numerical
// noise wherever the image is lit at the instant it was predicted for, on
// every illumination (impulse, full, rolling, global), without vsync, and
// through a rotation warp.
//
// Before prediction aimed at the middle of the lit interval it aimed at the
// middle line's write time: on the 90 Hz twins of scenarios/modern
// (120 deg/s), an exact predictor left 39.5 arcmin of registration error on
// full persistence and 8.5 on rolling persistence. The hand figures: full
// persistence lights a row half a refresh plus half the response after its
// write, 120 deg/s x (11.11 / 2 + 0.05) ms = 0.673 deg = 40.4 arcmin; rolling
// lights it after the response for 2 ms, 120 x (0.1 + 1) ms = 7.9 arcmin (the
// quoted figures are means over every row and probe, with their own scanout
// skew).
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "run_helpers.hpp"
#include "steady_samples.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using latsim::testing::max_of;
using latsim::testing::mean_of;
using latsim::testing::steady_samples;
using Json = nlohmann::json;

namespace {

constexpr double kRateDegS = 120.0;

/// A ring of probes 2 m around the head, every 10 degrees of yaw, `above_m`
/// above eye level.
Json probe_ring(double above_m) {
  Json points = Json::array();
  for (int i = 0; i < 36; ++i) {
    const double yaw = units::deg_to_rad(i * 10.0);
    points.push_back({-2.0 * std::sin(yaw), 1.6 + above_m, -2.0 * std::cos(yaw)});
  }
  return {{"points_m", points}};
}

/// A 90 Hz panel one pixel wide and three lines high (40 blank lines): a
/// probe is lit at column 0 of its line, so a probe on the line an image is
/// predicted for is lit exactly when predicted (the middle of that line's
/// lit interval), with no column or row skew. The vertical field of view is
/// tan(50 deg) x 3 wide in tangent: a probe at eye level projects to
/// y = 1.5 px, row 1 (the middle line, lines / 2 = (3 - 1) / 2 = 1, of whole
/// images and of a one-strip warp alike); one 3 m above at 2 m distance has
/// tangent 1.5 to 2.3 (horizontal angle within the 50 degree half field),
/// v = 0.42 to 0.65, y = 1.5 (1 - v) = 0.5 to 0.9 px: row 0.
Json tiny_display(const Json& persistence) {
  Json d = {{"refresh_hz", 90}, {"width_px", 1},   {"height_px", 3}, {"vblank_lines", 40},
            {"hblank_px", 0},   {"hfov_deg", 100}, {"scanout", "line"}};
  if (!persistence.is_null()) d["persistence"] = persistence;
  return d;
}

struct Illumination {
  const char* name;
  Json persistence;  ///< null: impulse (lit at the scanout instant)
};

std::vector<Illumination> illuminations() {
  return {{"impulse", nullptr},
          {"full persistence", {{"type", "full"}, {"response_ms", 0.1}}},
          {"rolling persistence", {{"type", "rolling"}, {"lit_ms", 2}, {"response_ms", 0.1}}},
          {"global low persistence", {{"type", "global"}, {"lit_ms", 2}, {"response_ms", 0.1}}}};
}

/// The pipelines under test: a shipped scenario or one written here, and the
/// height above eye level of the row their images are predicted for.
struct Pipeline {
  const char* name;
  const char* file;  ///< relative to scenarios/, or nullptr
  Json pipeline;     ///< used when there is no file
  double probes_above_m = 0.0;
  /// Each image is shown for exactly one field, predicted for its middle line.
  bool one_field_per_image = true;
};

std::vector<Pipeline> pipelines() {
  return {
      // Whole images swapped at a retrace, predicted for the middle line.
      {"double_buffer with vsync", nullptr, {{"type", "double_buffer"}, {"render", {{"fixed_ms", 4}}}}},
      // A rotation warp 2 ms before each retrace re-predicts the
      // orientation for the middle line; the position stays the
      // application's (a pure yaw about the head keeps it).
      {"frame_stages with a rotation warp", "modern/low_persistence_90hz.json", {}},
      // No vsync: each image first appears on the line the beam writes next
      // after it completes, predicted there. Frames of 3 ms (4 ms in the
      // unsynchronized scenario) against a field of 42 line periods of
      // 0.26 ms, 40 of them blank: row 0 always shows an image that
      // completed in the blanking before it (the last completion before row
      // 0 is written is at most one frame earlier, and at most one line
      // period of that frame's span is not blanking), and so first
      // appeared on row 0, predicted for its photon time.
      {"double_buffer without vsync", nullptr,
       {{"type", "double_buffer"}, {"vsync", false}, {"render", {{"fixed_ms", 3}}}}, 3.0, false},
      {"frame_stages without vsync", "modern/unsynchronized.json", {}, 3.0, false},
  };
}

latsim::scenario::ScenarioDocument scenario_of(const Pipeline& p, const Illumination& ill) {
  const Json motion = {{"type", "constant"}, {"axis", {0, 1, 0}}, {"rate_deg_s", kRateDegS}, {"position_m", {0, 1.6, 0}}};
  const std::vector<std::string> overrides = {
      "/duration_s=2",
      "/seed=5",
      "/motion=" + motion.dump(),
      "/tracker=" + Json{{"rate_hz", 1000}, {"internal_delay_ms", 1}}.dump(),
      "/transport=" + Json{{"type", "direct"}}.dump(),
      "/display=" + tiny_display(ill.persistence).dump(),
      "/probes=" + probe_ring(p.probes_above_m).dump(),
      "/host=" + Json{{"stereo", false}, {"prediction", {{"type", "constant_velocity"}}}}.dump()};
  if (p.file != nullptr)
    return latsim::run::load_scenario(std::string(LATSIM_SOURCE_DIR "/scenarios/") + p.file, overrides);
  Json s = {{"pipeline", p.pipeline}};
  for (const std::string& o : overrides) latsim::scenario::apply_override(s, o);
  return latsim::scenario::ScenarioDocument::from_json(s, LATSIM_SOURCE_DIR "/scenarios");
}

}  // namespace

TEST_CASE("an exact predictor aimed at the photon leaves only numerical noise", "[prediction][persistence]") {
  for (const Pipeline& p : pipelines()) {
    for (const Illumination& ill : illuminations()) {
      INFO(p.name << " on " << ill.name);
      const auto [out, steady] = steady_samples(scenario_of(p, ill), 500.0);
      const std::vector<double>& reg = steady.at("registration_error_arcmin");
      REQUIRE(reg.size() > 100);
      // The predicted orientation equals the true one at the target up to
      // double rounding of rotations of at most a few turns (1e-15 relative,
      // about 1e-14 rad = 3e-11 arcmin); the probe is lit at the target to
      // the picosecond (120 deg/s x 1 ps = 7e-12 arcmin). 1e-6 arcmin leaves
      // five orders of magnitude to spare and is a millionth of the error
      // of aiming at the write time.
      CHECK(max_of(reg) < 1e-6);
      // The pose was predicted as far ahead as the probe's latency: the
      // prediction error at the target is noise too.
      CHECK(max_of(steady.at("prediction_error_deg")) < 1e-6 / 60.0);
      if (p.one_field_per_image) {
        // The horizon is that of the prediction made for what is shown: the
        // orientation's sample to the middle line's photon. The three lines
        // are lit one line period apart (or together, for a global flash),
        // so their mean rotation latency is the middle line's. For the
        // rotation warp that is the warp's own sample, not the application's
        // (whose motion-to-photon latency is longer by the application's
        // frame).
        CHECK(mean_of(steady.at("prediction_horizon_ms")) ==
              Approx(mean_of(steady.at("rotation_latency_ms"))).margin(1e-5));
      }
    }
  }
}
