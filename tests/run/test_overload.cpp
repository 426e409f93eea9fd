// Overload is a result: a serial line slower than the tracker drops records
// and says so, and its latency stays bounded; a key of another mode is a
// warning, not an error.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "run_helpers.hpp"

using namespace latsim;
using Json = nlohmann::json;

namespace {

Json run_poll_scenario(std::vector<std::string> sets) {
  return run::run_scenario(
      run::load_scenario(LATSIM_SOURCE_DIR "/scenarios/hmd_60hz_serial_poll.json", sets), run::RunOptions{});
}

bool has_warning(const Json& summary, const std::string& part) {
  for (const Json& w : summary["warnings"])
    if (w.get<std::string>().find(part) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("a 40-byte record at 19200 baud and 60 Hz drops records, warns, and stays bounded", "[overload]") {
  // A record takes 40 x 10 bits / 19200 baud = 20.833 ms on the line, the
  // tracker sends one every 16.667 ms: utilisation 20.833 / 16.667 = 1.25.
  // In 10 s the tracker offers 600 records, the line sends at most
  // 10 s / 20.833 ms = 480; the buffer holds floor(256 / 40) = 6 more; the
  // rest (at least 600 - 480 - 6 - 1 in flight = 113) are dropped.
  const double transmit_ms = 40 * 10 / 19200.0 * 1e3;
  const std::vector<std::string> sets = {"/duration_s=10", "/transport/record_bytes=40"};
  const Json ten = run_poll_scenario(sets);
  const Json& f = ten["figures"];
  CHECK(f["line_utilisation"].get<double>() == Approx(1.25).epsilon(1e-6));
  CHECK(f["tracker_samples"].get<int64_t>() == 600);
  CHECK(f["records_dropped"].get<int64_t>() >= 113);
  CHECK(f["records_dropped"].get<int64_t>() <= 600 - 479);
  CHECK(has_warning(ten, "serial line overloaded"));
  // Bounded: a record waits behind at most the 6 buffered ones (the first of
  // them partly sent), so no wait exceeds 6 transmissions; without the buffer
  // the wait grew by 4.2 ms per record, past a second within 10 s.
  CHECK(f["line_wait_ms"]["max"].get<double>() <= 6 * transmit_ms + 1e-6);
  // The tracker's delay, the wait, the transmission, a 30 ms poll and one
  // refresh of rendering plus a field of scanout bound every latency.
  const double bound_ms = 6 * transmit_ms + transmit_ms + 30.0 + 3 * 1000.0 / 60.0 + 10.0;
  CHECK(f["motion_to_photon_ms"]["max"].get<double>() < bound_ms);
  // Steady state: twice the run, the same mean latency.
  std::vector<std::string> longer = sets;
  longer[0] = "/duration_s=20";
  const Json twenty = run_poll_scenario(longer);
  CHECK(twenty["figures"]["motion_to_photon_ms"]["mean"].get<double>() ==
        Approx(f["motion_to_photon_ms"]["mean"].get<double>()).margin(5.0));
}

TEST_CASE("a line that keeps up reports its utilisation and no warning", "[overload]") {
  // 32 bytes at 19200 baud: 16.667 ms per record, exactly the tracker period.
  const Json out = run_poll_scenario({"/duration_s=2"});
  CHECK(out["figures"]["line_utilisation"].get<double>() == Approx(1.0).epsilon(1e-6));
  CHECK(out["figures"]["records_dropped"].get<int64_t>() == 0);
  CHECK_FALSE(has_warning(out, "overloaded"));
}

TEST_CASE("switching the host mode with --set leaves the other mode's key as a warning", "[overload][params]") {
  // The scenario sets poll_interval_ms, which only host=poll reads: a key of
  // another mode of the same object is not a misspelling.
  const Json out = run_poll_scenario({"/duration_s=1", "/transport/host=\"interrupt\""});
  CHECK(out["scenario"]["transport"]["host"] == "interrupt");
  CHECK(has_warning(out, "/transport/poll_interval_ms: ignored: read only when type=serial, host=poll"));
  // An unknown key stays an error.
  CHECK_THROWS_AS(run_poll_scenario({"/duration_s=1", "/transport/pol_interval_ms=3"}), scenario::ScenarioError);
}
