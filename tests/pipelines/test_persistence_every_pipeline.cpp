// One meaning per figure, persistence included: in every pipeline the
// photon time of motion-to-photon latency is the middle of the pixel's lit
// interval, so switching the display from full persistence to a 2 ms global
// flash moves the mean latency by an amount that follows from the raster
// alone.
#include <catch2/catch.hpp>

#include <set>
#include <string>
#include <vector>

#include "latsim/run/builtin_pipelines.hpp"
#include "run_helpers.hpp"

using latsim::testing::fig;
using Json = nlohmann::json;

namespace {

constexpr double kLitMs = 2.0;

struct Case {
  const char* name;
  const char* file;  ///< relative to scenarios/, or nullptr
  Json scenario;     ///< used when there is no file
  /// Latency sampled at every pixel (frameless), not once per line.
  bool per_pixel = false;
};

Json small_60hz() {
  return {{"refresh_hz", 60}, {"interlaced", false}, {"width_px", 64}, {"height_px", 48}, {"vblank_lines", 4},
          {"hblank_px", 16},  {"hfov_deg", 60},      {"scanout", "line"}};
}

std::vector<Case> every_pipeline() {
  return {
      {"double_buffer", "hmd_60hz_direct.json", {}},
      {"double_buffer without vsync", "hmd_60hz_tearing.json", {}},
      {"pxpl5_rc", "pxpl5/rc_min_latency.json", {}},
      {"pxpl5_slats", "pxpl5/slats_140.json", {}},
      // Every pixel sampled, so that the mean is over the whole raster.
      {"frameless", nullptr,
       {{"display", small_60hz()},
        {"pipeline", {{"type", "frameless"}, {"full_images_per_s", 120}, {"sample_pixels", 64 * 48}}}},
       true},
      {"frameless (double_buffer strategy)", nullptr,
       {{"display", small_60hz()},
        {"pipeline", {{"type", "frameless"}, {"strategy", "double_buffer"}, {"full_images_per_s", 30}}}}},
      {"arp", "arp/arp_basic.json", {}},
      {"priority", "arp/priority.json", {}},
      {"region_priority", "arp/gallery.json", {}},
      {"frame_stages with vsync", "modern/vsync.json", {}},
      {"frame_stages unsynchronized", "modern/unsynchronized.json", {}},
      {"frame_stages with time warp", "modern/timewarp.json", {}},
      {"frame_stages with continuous time warp", "modern/continuous_timewarp.json", {}},
      {"present_replay", "measured/current_cpu_gpu.json", {}},
      {"streaming", nullptr,
       {{"display", small_60hz()},
        {"pipeline", {{"type", "streaming"},
                      {"server", {{"render", {{"fixed_ms", 4}}}}},
                      {"encoder", {{"bitrate_mbps", 50}, {"fixed_ms", 3}}},
                      {"client", {{"decoder_fixed_ms", 4}, {"client_compositor_ms", 1}}}}}}},
      {"passthrough", nullptr,
       {{"display", small_60hz()},
        {"pipeline", {{"type", "passthrough"},
                      {"camera", {{"height_px", 480}, {"exposure_ms", 2}, {"row_readout_us", 10}}},
                      {"isp", {{"fixed_ms", 3}}},
                      {"compositor", {{"reprojection_ms", 1}}}}}}},
  };
}

Json run_with(const Case& c, const Json& persistence) {
  const std::vector<std::string> overrides = {"/duration_s=3", "/display/persistence=" + persistence.dump()};
  if (c.file != nullptr)
    return latsim::run::run_scenario(
        latsim::run::load_scenario(std::string(LATSIM_SOURCE_DIR "/scenarios/") + c.file, overrides),
        latsim::run::RunOptions{});
  Json s = c.scenario;
  s["duration_s"] = 3;
  s["seed"] = 2;
  s["motion"] = {{"type", "constant"}, {"axis", {0, 1, 0}}, {"rate_deg_s", 30}};
  s["tracker"] = {{"rate_hz", 60}};
  for (const std::string& o : overrides) latsim::scenario::apply_override(s, o);
  return latsim::testing::run(s);
}

/// The hand-derived move of mean motion-to-photon latency from full
/// persistence to a global flash of kLitMs (no response time either way).
///
/// A line written at w in field f (retrace r_f, field period T, F fields a
/// frame) is lit
///   full:   [w, w + F T]         middle w + F T / 2 (held until rewritten)
///   global: [r_f + T, r_f + T + lit]  middle r_f + T + lit / 2 (the flash
///           follows the field's last line; blanking opens the next field)
/// so its latency moves by T + lit / 2 - F T / 2 - (w - r_f), whatever the
/// pose it shows. Without prediction both runs show the same poses on the
/// same lines; averaged over a field's L active lines after V blank lines,
/// each a line period T / (L + V), w - r_f averages (V + (L - 1) / 2) line
/// periods; sampled at every pixel (frameless), plus (W - 1) / 2 pixel
/// times of W + H_blank per line. For instance the 60 Hz progressive HMD
/// (480 lines, 22 blank): 16.667 + 1 - 8.333 - 261.5 x 0.03320 = 0.651 ms;
/// Pixel-Planes 5's interlaced NTSC (240 lines a field, 22 blank, F = 2):
/// 16.667 + 1 - 16.667 - 141.5 x 0.0636 = -8.00 ms; the 62.5 Hz reference
/// display without blanking: 16 + 1 - 8 - 239.5 x 0.0333 = 1.017 ms.
double expected_move_ms(const Json& display, bool per_pixel) {
  const double field_ms = 1e3 / display.at("refresh_hz").get<double>();
  const bool interlaced = display.at("interlaced").get<bool>();
  const int frames_fields = interlaced ? 2 : 1;
  const int lines = display.at("height_px").get<int>() / frames_fields;
  const int vblank = display.at("vblank_lines").get<int>();
  const double line_ms = field_ms / (lines + vblank);
  double offset_ms = (vblank + (lines - 1) / 2.0) * line_ms;
  if (per_pixel) {
    const int width = display.at("width_px").get<int>();
    offset_ms += (width - 1) / 2.0 * line_ms / (width + display.at("hblank_px").get<int>());
  }
  return field_ms + kLitMs / 2.0 - frames_fields * field_ms / 2.0 - offset_ms;
}

}  // namespace

TEST_CASE("the cases cover every registered pipeline", "[persistence]") {
  std::set<std::string> covered;
  for (const Case& c : every_pipeline()) {
    const Json s = c.file != nullptr
                       ? latsim::run::load_scenario(std::string(LATSIM_SOURCE_DIR "/scenarios/") + c.file, {}).resolved()
                       : c.scenario;
    covered.insert(s.at("pipeline").at("type").get<std::string>());
  }
  for (const std::string& name : latsim::run::builtin_pipelines().names()) {
    INFO(name);
    CHECK(covered.count(name) == 1);
  }
}

TEST_CASE("full persistence to a 2 ms global flash moves motion-to-photon as the raster says, in every pipeline",
          "[persistence]") {
  for (const Case& c : every_pipeline()) {
    INFO(c.name);
    const Json full = run_with(c, {{"type", "full"}});
    const Json global = run_with(c, {{"type", "global"}, {"lit_ms", kLitMs}});
    const Json& display = full.at("scenario").at("display");
    const Json& a = fig(full, "motion_to_photon_ms");
    const Json& b = fig(global, "motion_to_photon_ms");
    // The same samples on the same lines (nothing else changes).
    REQUIRE(a.at("count") == b.at("count"));
    const double fields = full.at("figures").at("fields").get<double>();
    const double field_ms = 1e3 / display.at("refresh_hz").get<double>();
    // Tolerance: the mean over lines is exact for whole fields; the first
    // field shown and the last one, cut by the end of the run, may hold only
    // some of their lines, whose offsets differ from the field's mean by at
    // most half a field: two fields in `fields`, T / 2 each.
    const double tolerance_ms = 2.0 * (field_ms / 2.0) / fields;
    CHECK(b.at("mean").get<double>() - a.at("mean").get<double>() ==
          Approx(expected_move_ms(display, c.per_pixel)).margin(tolerance_ms));
  }
}
