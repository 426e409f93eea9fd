// Constant-velocity prediction against a constant-rate yaw, in every
// pipeline: with the pipeline's own expected photon time as the horizon the
// steady registration error vanishes; without prediction it is rate x latency.
#include <catch2/catch.hpp>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "latsim/run/builtin_pipelines.hpp"
#include "run_helpers.hpp"
#include "steady_samples.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using latsim::testing::fig;
using latsim::testing::max_of;
using latsim::testing::mean_of;
using latsim::testing::run;
using latsim::testing::steady_samples;
using Json = nlohmann::json;

namespace {

constexpr double kRateDegS = 60.0;

/// Probes every 15 degrees of yaw on a ring 2 m around the head at eye
/// height: a pure yaw keeps them on the screen's middle row, the line each
/// pipeline predicts an image for.
Json eye_level_probes() {
  Json points = Json::array();
  for (int i = 0; i < 24; ++i) {
    const double yaw = units::deg_to_rad(i * 15.0);
    points.push_back({-2.0 * std::sin(yaw), 1.6, -2.0 * std::cos(yaw)});
  }
  return {{"points_m", points}};
}

/// The same yaw, tracker and probes for every pipeline, as overrides.
std::vector<std::string> yaw_overrides(const std::string& predictor) {
  const Json motion = {{"type", "constant"}, {"axis", {0, 1, 0}}, {"rate_deg_s", kRateDegS}, {"position_m", {0, 1.6, 0}}};
  const Json host = {{"stereo", false}, {"prediction", {{"type", predictor}}}};
  return {"/duration_s=3",
          "/seed=3",
          "/motion=" + motion.dump(),
          "/tracker=" + Json{{"rate_hz", 60}, {"internal_delay_ms", 2}}.dump(),
          "/transport=" + Json{{"type", "direct"}}.dump(),
          "/probes=" + eye_level_probes().dump(),
          "/host=" + host.dump()};
}

/// A pipeline: a shipped scenario (its display, scene and /pipeline keys)
/// or one written here.
struct Case {
  const char* name;
  const char* file;  ///< relative to scenarios/, or nullptr
  Json scenario;     ///< used when there is no file
  /// Address recalculation: the orientation is predicted per line at
  /// scanout, the position per display memory, so their horizons differ.
  bool per_line_orientation = false;
  /// Strips warped (or rendered) one by one just ahead of the beam, each
  /// predicted for its own middle line; 0: whole images.
  int strips = 0;
};

Json progressive_60hz(int width, int height) {
  return {{"refresh_hz", 60}, {"interlaced", false}, {"width_px", width}, {"height_px", height}, {"hfov_deg", 60},
          {"scanout", "line"}};
}

std::vector<Case> every_pipeline() {
  std::vector<Case> cases;
  cases.push_back({"double_buffer", nullptr,
                   {{"display", progressive_60hz(640, 480)},
                    {"pipeline", {{"type", "double_buffer"}, {"render", {{"fixed_ms", 8}}}}}}});
  cases.push_back({"double_buffer rendering one frame ahead", nullptr,
                   {{"display", progressive_60hz(640, 480)},
                    {"pipeline", {{"type", "double_buffer"}, {"queued_frames", 1}, {"render", {{"fixed_ms", 8}}}}}}});
  cases.push_back({"pxpl5_slats", "pxpl5/slats_140.json", {}});
  cases.push_back({"pxpl5_rc", "pxpl5/rc_min_latency.json", {}});
  // Two full updates per refresh: every pixel is recomputed before it could
  // be shown a second time, so each computed pixel is lit in one field only.
  cases.push_back({"frameless", nullptr,
                   {{"display", progressive_60hz(64, 48)},
                    {"pipeline", {{"type", "frameless"}, {"full_images_per_s", 120}, {"sample_pixels", 512}}}}});
  cases.push_back({"frameless budget as double buffering", nullptr,
                   {{"display", progressive_60hz(64, 48)},
                    {"pipeline", {{"type", "frameless"}, {"strategy", "double_buffer"}, {"full_images_per_s", 60}}}}});
  cases.push_back({"arp", "arp/arp_basic.json", {}, true});
  cases.push_back({"priority", "arp/priority.json", {}, true});
  cases.push_back({"region_priority", "arp/gallery.json", {}, true});
  cases.push_back({"frame_stages with vsync", "modern/vsync.json", {}});
  cases.push_back({"frame_stages with time warp", "modern/timewarp.json", {}});
  cases.push_back({"frame_stages with continuous time warp", "modern/continuous_timewarp.json", {}, false, 8});
  // A steady application replayed on its Legacy Flip queue (tests/pipelines/data/README.md): it starts each
  // frame at a retrace, three behind the frames queued before it.
  cases.push_back({"present_replay", nullptr,
                   {{"display", progressive_60hz(640, 480)},
                    {"pipeline", {{"type", "present_replay"},
                                  {"capture", {{"file", LATSIM_SOURCE_DIR "/tests/pipelines/data/steady_present.csv"}}}}}}});
  // A streamed headset without the client's re-projection (which would make the registration error the
  // orientation's, not the whole pose's): the server's pose predicted for its measured photon time.
  cases.push_back({"streaming", nullptr,
                   {{"display", progressive_60hz(640, 480)},
                    {"pipeline", {{"type", "streaming"},
                                  {"server", {{"render", {{"fixed_ms", 4}}}, {"server_compositor_ms", 1}}},
                                  {"encoder", {{"bitrate_mbps", 50}, {"fixed_ms", 3}}},
                                  {"client", {{"decoder_fixed_ms", 4}, {"client_compositor_ms", 1}, {"reprojection", false}}}}}}});
  // A see-through headset: the camera image re-projected to the head pose predicted for the refresh.
  cases.push_back({"passthrough", nullptr,
                   {{"display", progressive_60hz(640, 480)},
                    {"pipeline", {{"type", "passthrough"},
                                  {"camera", {{"exposure_ms", 2}, {"row_readout_us", 2}}},
                                  {"isp", {{"fixed_ms", 3}}},
                                  {"compositor", {{"reprojection_ms", 1}, {"composition_ms", 0.5}}}}}}});
  return cases;
}

latsim::scenario::ScenarioDocument scenario_of(const Case& c, const std::string& predictor) {
  const std::vector<std::string> overrides = yaw_overrides(predictor);
  if (c.file != nullptr)
    return latsim::run::load_scenario(std::string(LATSIM_SOURCE_DIR "/scenarios/") + c.file, overrides);
  Json s = c.scenario;
  for (const std::string& o : overrides) latsim::scenario::apply_override(s, o);
  return latsim::scenario::ScenarioDocument::from_json(s, LATSIM_SOURCE_DIR "/scenarios");
}

/// What a scenario shows after its first second, and its whole summary.
latsim::testing::SteadyRun run_case(const Case& c, const std::string& predictor) {
  return steady_samples(scenario_of(c, predictor), 1000.0);
}

/// How far, in lines, the middle row is lit from the line its image (or
/// strip) was predicted for: none for whole images; for a strip, the
/// distance from the strip's middle line (the warp's own target).
int lines_from_target(const Case& c, const Json& summary) {
  if (c.strips == 0) return 0;
  const Json& d = summary.at("scenario").at("display");
  const int lines = d.at("height_px").get<int>() / (d.at("interlaced").get<bool>() ? 2 : 1);
  const int middle = lines / 2;
  const int strip = middle * c.strips / lines;
  const int first = strip * lines / c.strips, next = (strip + 1) * lines / c.strips;
  return std::abs(middle - (first + (next - first - 1) / 2));
}

/// Address recalculation without prediction: the age of the newest sample
/// the host can see when the middle line is fetched (the same in every field:
/// tracker and display both run at 60 Hz, each at its own phase).
double middle_line_age_ms(const Json& summary) {
  const Json& sc = summary.at("scenario");
  const Json& d = sc.at("display");
  const Json& t = sc.at("tracker");
  const double field_ms = 1e3 / d.at("refresh_hz").get<double>();
  const double sample_ms = 1e3 / t.at("rate_hz").get<double>();
  const double delay_ms = t.at("internal_delay_ms").get<double>();
  const int lines = d.at("height_px").get<int>() / (d.at("interlaced").get<bool>() ? 2 : 1);
  const int vblank = d.at("vblank_lines").get<int>();
  const double middle_ms = d.at("phase_ms").get<double>() + (vblank + lines / 2) * field_ms / (lines + vblank);
  // Samples are measured at phase + n * period and visible `delay_ms` later.
  const double since = std::fmod(middle_ms - delay_ms - t.at("phase_ms").get<double>(), sample_ms);
  return delay_ms + (since < 0.0 ? since + sample_ms : since);
}

double line_period_ms(const Json& summary) {
  const Json& d = summary.at("scenario").at("display");
  const double field_ms = 1e3 / d.at("refresh_hz").get<double>();
  const int lines = d.at("height_px").get<int>() / (d.at("interlaced").get<bool>() ? 2 : 1);
  return field_ms / (lines + d.at("vblank_lines").get<int>());
}

}  // namespace

TEST_CASE("the cases below cover every registered pipeline", "[prediction]") {
  // The pipelines come from the registry, not from a list kept here: a
  // pipeline added to the registry without a case fails this test.
  std::set<std::string> covered;
  for (const Case& c : every_pipeline())
    covered.insert(scenario_of(c, "none").resolved().at("pipeline").at("type").get<std::string>());
  for (const std::string& name : latsim::run::builtin_pipelines().names()) {
    INFO(name);
    CHECK(covered.count(name) == 1);
  }
  CHECK(covered.size() == latsim::run::builtin_pipelines().names().size());
}

TEST_CASE("constant velocity cancels the registration error of a constant yaw in every pipeline", "[prediction]") {
  for (const Case& c : every_pipeline()) {
    INFO(c.name);
    const auto [out, steady] = run_case(c, "constant_velocity");
    const std::vector<double>& reg = steady.at("registration_error_arcmin");
    REQUIRE(reg.size() > 100);
    // The predicted pose is exact at the expected photon time of the
    // image's middle line (per pixel for frameless). A probe on the middle
    // row is lit at most one line period from it (its column's offset along
    // the line; interlaced, the nearest row of the field's parity is on the
    // middle line): an error of at most rate x 2 line periods, once the
    // predictor has two samples and the pipeline has filled. A strip is
    // predicted for its own middle line, which the middle row may be up to
    // half a strip from: that scanout skew is the strip's, not latency.
    const double bound_arcmin =
        kRateDegS * 60.0 * (2.0 + lines_from_target(c, out)) * line_period_ms(out) * 1e-3;
    CHECK(max_of(reg) < bound_arcmin);
    // The host predicted as far as the latency it hides.
    if (!c.per_line_orientation)
      CHECK(mean_of(steady.at("prediction_horizon_ms")) == Approx(mean_of(steady.at("motion_to_photon_ms"))).epsilon(0.05));
  }
}

TEST_CASE("without prediction the registration error of a constant yaw is rate times latency", "[prediction]") {
  for (const Case& c : every_pipeline()) {
    // Strips are lit later the further down each strip: latency is a
    // sawtooth over the field, and middle-row probes, at the top of a strip,
    // do not see its mean (tests/pipelines/frame_stages derive those ranges).
    if (c.strips != 0) continue;
    INFO(c.name);
    const auto [out, steady] = run_case(c, "none");
    // Each probe (pixel) is off by rate x its own motion-to-photon latency.
    // An image's latency grows linearly down the screen, so the middle row's
    // is the mean over lines. Address recalculation reads the newest sample
    // per line instead: the newest sample visible as the middle line is
    // fetched serves it (its age depends on the tracker's and the display's
    // phases, drawn per replication).
    // Frameless measures at sampled pixels up to 23 degrees above and below
    // the horizon, where a yaw moves directions by rate x cos(elevation): a
    // few percent less.
    const double latency_ms = c.per_line_orientation ? middle_line_age_ms(out)
                                                     : mean_of(steady.at("motion_to_photon_ms"));
    CHECK(mean_of(steady.at("registration_error_arcmin")) == Approx(kRateDegS * 60.0 * latency_ms * 1e-3).epsilon(0.05));
    // Prediction "none" still reports what not predicting costs.
    CHECK(mean_of(steady.at("prediction_error_deg")) > 0.5 * kRateDegS * latency_ms * 1e-3);
  }
}
