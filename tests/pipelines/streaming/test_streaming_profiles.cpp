// Every shipped streaming profile (scenarios/streaming/) runs, and what it
// reports follows from the values in its file by hand:
// - every frame has bitrate / refresh rate bits (constant bit rate);
// - the encoder's time is fixed + pixels / pixel rate;
// - the PHY rate of HE MCS 11, 80 MHz, 2 streams, 800 ns GI is 1201 Mb/s:
//   N_DBPS = floor(980 data subcarriers x 10 bits x 2 streams x 5/6) = 16333
//   data bits per 13.6 us symbol (12.8 us + 0.8 us GI): 1200.96 Mb/s;
// - with 1 % of MPDUs lost and 7 retries a packet is lost for good with
//   0.01^8 = 1e-16: no frame is incomplete;
// - every profile's panel is lit globally (one flash once the field is
//   written), so the runtime's predicted display time, where the tool's total
//   ends, is every pixel's photon time, and the camera's motion-to-photon
//   latency exceeds the tool's total by the age of the tracker sample when
//   the report left: at least 0, under one tracker period (1 ms at 1000 Hz).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include "run_helpers.hpp"

using latsim::testing::fig;
using Json = nlohmann::json;

namespace {

double stat(const Json& out, const char* name) { return fig(out, name).at("mean").get<double>(); }

}  // namespace

TEST_CASE("streaming: every shipped profile runs and reports what its values give by hand") {
  int profiles = 0;
  for (const auto& path : latsim::testing::shipped_scenarios()) {
    if (path.parent_path().filename() != "streaming") continue;
    ++profiles;
    INFO(path.string());
    std::ifstream in(path);
    const Json file = Json::parse(in);
    const Json& enc = file.at("/pipeline/encoder"_json_pointer);
    const double hz = file.at("/display/refresh_hz"_json_pointer).get<double>();
    const Json out = latsim::run::run_scenario(latsim::run::load_scenario(path.string(), {"/duration_s=2"}),
                                               latsim::run::RunOptions{});
    const Json& f = out.at("figures");
    CHECK(f.at("frame_bytes").get<double>() ==
          std::round(enc.at("bitrate_mbps").get<double>() * 1e6 / hz / 8.0));
    const double pixels = enc.at("width_px").get<double>() * enc.at("height_px").get<double>();
    CHECK(f.at("encoder_frame_time_ms").get<double>() ==
          Approx(enc.at("fixed_ms").get<double>() + pixels / enc.at("pixel_rate_mpx_s").get<double>() / 1e3));
    CHECK(f.at("link").at("data_rate_mbps").get<double>() == Approx(16333 / 13.6).epsilon(1e-9));
    CHECK(f.at("frames_incomplete").get<int64_t>() == 0);
    CHECK(f.at("frames_shown").get<int64_t>() > 0);
    const double gap = stat(out, "motion_to_photon_ms") - stat(out, "reported_total_ms");
    CHECK(gap >= 0.0);
    CHECK(gap < 1.0);
  }
  // quest2 and quest3 with Air Link, Virtual Desktop and ALVR; pico4 with ALVR.
  CHECK(profiles == 7);
}
