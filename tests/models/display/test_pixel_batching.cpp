// Pixel fidelity at the price of its information: scanning a line as one
// batch (split only where what it shows changes) must give every figure of
// the reference path that spends one event per pixel, bit for bit, on
// scenarios where swaps happen mid-line, with stereo, interlacing, strides,
// address recalculation and frameless rendering.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

using Json = nlohmann::json;

namespace {

Json run_file(const std::string& file, std::vector<std::string> overrides) {
  const auto doc = latsim::run::load_scenario(LATSIM_SOURCE_DIR "/scenarios/" + file, overrides);
  return latsim::run::run_scenario(doc, latsim::run::RunOptions{});
}

// Runs `file` at pixel fidelity both ways and compares every figure.
void check_identical(const std::string& file, std::vector<std::string> overrides) {
  // A small screen unless the case asks for another (later overrides win).
  overrides.insert(overrides.begin(), {"/display/scanout=\"pixel\"", "/display/width_px=64", "/display/height_px=48"});
  const Json batched = run_file(file, overrides);
  overrides.push_back("/display/pixel_events=true");
  const Json reference = run_file(file, overrides);
  INFO(file);
  const int64_t batched_events = batched["events_per_model"]["display"].get<int64_t>();
  const int64_t reference_events = reference["events_per_model"]["display"].get<int64_t>();
  CHECK(batched_events * 10 < reference_events);
  REQUIRE(batched["figures"].contains("motion_to_photon_ms"));
  CHECK(batched["figures"]["motion_to_photon_ms"]["count"].get<int64_t>() > 1000);
  if (batched["figures"] != reference["figures"]) {
    // Name the first differing figure before failing.
    for (const auto& [name, value] : reference["figures"].items())
      if (batched["figures"][name] != value) FAIL_CHECK(name << ": batched " << batched["figures"][name].dump()
                                                              << " vs per-pixel events " << value.dump());
  }
  CHECK(batched["figures"] == reference["figures"]);
}

}  // namespace

TEST_CASE("batched pixels equal per-pixel events: tearing, mono", "[pixel]") {
  // Without vsync every finished image replaces the front buffer mid-scan.
  check_identical("hmd_60hz_tearing.json", {"/duration_s=1", "/frames/enabled=false"});
}

TEST_CASE("batched pixels equal per-pixel events: tearing, stereo interlaced, stride 3, kept samples", "[pixel]") {
  check_identical("ntsc_stereo_interlaced.json", {"/duration_s=1", "/frames/enabled=false", "/pipeline/vsync=false",
                                                  "/display/pixel_stride=3", "/output/keep_samples=true"});
}

TEST_CASE("batched pixels equal per-pixel events: address recalculation reads orientations mid-line", "[pixel]") {
  // A 997 Hz tracker: new orientations arrive all through each field's scan,
  // about a quarter of them while a line's pixels are lit.
  check_identical("arp/arp_basic.json", {"/duration_s=0.5", "/pipeline/frame_times_s=[]", "/tracker/rate_hz=997"});
}

TEST_CASE("batched pixels equal per-pixel events: address recalculation predicts every pixel's own photon time",
          "[pixel]") {
  // With prediction each pixel's orientation is extrapolated to its own
  // photon time, so a batched line is recorded sample by sample.
  check_identical("arp/arp_basic.json", {"/duration_s=0.3", "/pipeline/frame_times_s=[]", "/tracker/rate_hz=997",
                                         "/host/prediction={\"type\": \"constant_velocity\"}"});
}

TEST_CASE("batched pixels equal per-pixel events: frameless rendering", "[pixel]") {
  check_identical("frameless/side_by_side.json", {"/duration_s=0.5", "/frames/enabled=false"});
}

TEST_CASE("batched pixels equal per-pixel events: staged frames, tearing and time-warp strips", "[pixel]") {
  check_identical("modern/unsynchronized.json", {"/duration_s=0.3"});
  // Eight strips, each warped into the front buffer just before it is lit.
  check_identical("modern/continuous_timewarp.json", {"/duration_s=0.3"});
}

TEST_CASE("batched pixels equal per-pixel events: persistence shifts or holds every photon time", "[pixel]") {
  // Rolling flashes (a fixed delay after each write) with their smear, and a
  // global flash (one instant for the whole field) on a tearing display.
  check_identical("modern/low_persistence_90hz.json", {"/duration_s=0.3"});
  check_identical("hmd_60hz_tearing.json", {"/duration_s=0.5", "/frames/enabled=false",
                                            "/display/persistence={\"type\": \"global\", \"lit_ms\": 2}"});
}

TEST_CASE("batched pixels equal per-pixel events: regions written into the displayed buffer mid-scan", "[pixel]") {
  // Slats writes 128-pixel regions of the interlaced frame buffer while it is
  // scanned: lines cross regions of the old and the new field's image.
  // Three 128-pixel region columns, sampled every 3 pixels (samples straddle
  // region borders).
  check_identical("pxpl5/slats_140.json",
                  {"/duration_s=0.2", "/display/width_px=320", "/display/height_px=96", "/display/pixel_stride=3"});
}

TEST_CASE("a field computed at its retrace equals line scanout: address recalculation reads orientations mid-field",
          "[pixel]") {
  // Field scanout hands each field over as one span per eye at its retrace,
  // before the samples measured during the field exist; the recorder cuts it
  // into runs of lines that share the newest sample when each line is
  // written. Line scanout looks each line up at its own event. A 997 Hz
  // tracker makes about 16 runs per field.
  // With prediction every line has an orientation of its own.
  for (const bool predicts : {false, true}) {
    INFO("prediction " << predicts);
    std::vector<std::string> overrides{"/duration_s=0.5", "/pipeline/frame_times_s=[]", "/tracker/rate_hz=997"};
    if (predicts) overrides.emplace_back("/host/prediction={\"type\": \"constant_velocity\"}");
    overrides.push_back("/display/scanout=\"field\"");
    const Json field = run_file("arp/arp_basic.json", overrides);
    overrides.back() = "/display/scanout=\"line\"";
    const Json line = run_file("arp/arp_basic.json", overrides);
    for (const char* name : {"motion_to_photon_ms", "rotation_latency_ms", "translation_latency_ms", "display_ms",
                             "image_age_ms", "registration_error_arcmin", "registration_error_px",
                             "prediction_error_deg", "prediction_horizon_ms"}) {
      INFO(name);
      REQUIRE(field["figures"].contains(name) == line["figures"].contains(name));
      if (line["figures"].contains(name)) CHECK(field["figures"][name] == line["figures"][name]);
    }
    CHECK(line["figures"]["rotation_latency_ms"]["count"].get<int64_t>() > 10000);
    CHECK(line["figures"].contains("prediction_error_deg") == predicts);
    CHECK(field["events_per_model"]["display"].get<int64_t>() * 100 <
          line["events_per_model"]["display"].get<int64_t>());
  }
}
