// The recorder takes a span that continues its eye's open run (the next line
// of the image and field the eye's last span showed) by extending that run,
// without the per-span path. With the ledger on every span takes the whole
// path (a row per span needs it), so a run with the ledger is the reference:
// every figure must be the same bit for bit, on scenarios where the image,
// the field or the eye changes between consecutive spans in every way.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

using Json = nlohmann::json;

namespace {

Json run_file(const std::string& file, const std::vector<std::string>& overrides, bool ledger) {
  const auto doc = latsim::run::load_scenario(LATSIM_SOURCE_DIR "/scenarios/" + file, overrides);
  latsim::run::RunOptions options;
  options.write_ledger = ledger;
  return latsim::run::run_scenario(doc, options);
}

void check_same_figures(const std::string& file, std::vector<std::string> overrides) {
  overrides.insert(overrides.begin(), "/display/scanout=\"line\"");
  const Json continued = run_file(file, overrides, false);
  const Json whole_path = run_file(file, overrides, true);
  INFO(file);
  REQUIRE(continued["figures"].contains("motion_to_photon_ms"));
  CHECK(continued["figures"]["motion_to_photon_ms"]["count"].get<int64_t>() > 1000);
  for (const auto& [name, value] : whole_path["figures"].items()) {
    INFO(name);
    CHECK(continued["figures"][name] == value);
  }
  CHECK(continued["figures"].size() == whole_path["figures"].size());
}

}  // namespace

TEST_CASE("continued line spans equal the whole path: double buffering with probes", "[scanout]") {
  // A new image every field; 72 probes, some lit on most fields.
  check_same_figures("hmd_60hz_direct.json", {"/duration_s=2"});
}

TEST_CASE("continued line spans equal the whole path: swaps mid-scan, stereo interlaced", "[scanout]") {
  check_same_figures("hmd_60hz_tearing.json", {"/duration_s=1", "/frames/enabled=false"});
  check_same_figures("ntsc_stereo_interlaced.json",
                     {"/duration_s=1", "/frames/enabled=false", "/pipeline/vsync=false"});
}

TEST_CASE("continued line spans equal the whole path: regions, strips and persistence", "[scanout]") {
  // Slats writes regions of the buffer being scanned (a line shows two
  // images); time-warp strips; rolling low-persistence flashes.
  check_same_figures("pxpl5/slats_140.json", {"/duration_s=0.4", "/display/width_px=320", "/display/height_px=96"});
  check_same_figures("modern/continuous_timewarp.json", {"/duration_s=0.3"});
  check_same_figures("modern/low_persistence_90hz.json", {"/duration_s=0.3"});
}

TEST_CASE("continued line spans equal the whole path: address recalculation and time warp", "[scanout]") {
  check_same_figures("arp/arp_basic.json", {"/duration_s=0.5", "/pipeline/frame_times_s=[]", "/tracker/rate_hz=997"});
  check_same_figures("modern/timewarp.json", {"/duration_s=0.5"});
}
