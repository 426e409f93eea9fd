// Independent clocks: phases drawn per replication and recorded, rate errors
// as exact periods, and what a poll timer of unrelated phase really costs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "latsim/des/clock.hpp"
#include "run_helpers.hpp"

using namespace latsim;
using Json = nlohmann::json;

namespace {

Json run_file(const char* file, std::vector<std::string> sets, uint64_t replication) {
  run::RunOptions options;
  options.replication = replication;
  return run::run_scenario(run::load_scenario(std::string(LATSIM_SOURCE_DIR "/scenarios/") + file, sets),
                                 options);
}

}  // namespace

TEST_CASE("a rate error makes the period another exact rational", "[clocks]") {
  // 60 Hz running 50 ppm fast: T = (1/60) / (1 + 50e-6) = 1e9 / (60 * 1000050000) s.
  const des::RationalSeconds t = des::period_with_rate_error({1, 60}, 50.0);
  CHECK(static_cast<__int128>(t.num) * 60 * 1000050000 == static_cast<__int128>(t.den) * 1000000000);
  // The millionth period lies exactly where the rational says, not a rounded period times a million.
  const des::PeriodicSchedule s(des::Time::zero(), t);
  const __int128 ticks = static_cast<__int128>(1'000'000) * t.num * des::Time::kTicksPerSecond / t.den;
  CHECK(s.at(1'000'000).ticks() == static_cast<int64_t>(ticks));
  CHECK(s.at(1'000'000) < des::Time::from_seconds(1e6 / 60.0));  // fast: earlier than nominal
  // NTSC's 60000/1001 Hz, 20 ppm slow.
  const des::RationalSeconds n = des::period_with_rate_error({1001, 60000}, -20.0);
  CHECK(static_cast<__int128>(n.num) * 60000 * 999980000 == static_cast<__int128>(n.den) * 1001 * 1000000000);
  CHECK(des::period_with_rate_error({1, 60}, 0.0).num == 1);
  CHECK_THROWS_AS(des::period_with_rate_error({1, 60}, 2e5), std::invalid_argument);
}

TEST_CASE("phases are drawn per replication from each clock's stream and recorded", "[clocks]") {
  const std::vector<std::string> sets = {"/duration_s=1", "/tracker/jitter_ms=0.5"};
  const Json a = run_file("hmd_60hz_serial_poll.json", sets, 0);
  const Json b = run_file("hmd_60hz_serial_poll.json", sets, 1);
  const Json& ra = a["scenario"];
  const Json& rb = b["scenario"];
  for (const char* clock : {"/tracker/phase_ms", "/display/phase_ms", "/transport/poll_phase_ms"}) {
    const Json::json_pointer p(clock);
    INFO(clock);
    REQUIRE(ra.contains(p));
    CHECK(ra[p].get<double>() >= 0.0);
    CHECK(ra[p] != rb[p]);  // another replication, another phase
  }
  CHECK(ra["/tracker/phase_ms"_json_pointer].get<double>() < 1000.0 / 60.0);
  CHECK(ra["/transport/poll_phase_ms"_json_pointer].get<double>() < 30.0);

  // The resolved scenario alone repeats the run: same seed and replication,
  // phases now fixed, figures identical.
  const Json again = run::run_scenario(
      scenario::ScenarioDocument::from_json(ra, LATSIM_SOURCE_DIR "/scenarios"), [] {
        run::RunOptions o;
        o.replication = 0;
        return o;
      }());
  CHECK(again["figures"] == a["figures"]);
  CHECK(again["fingerprint"] == a["fingerprint"]);
  CHECK(again["scenario"] == ra);
}

TEST_CASE("a 30 ms poll adds half a poll interval of mean latency and a whole one of spread", "[clocks][analytic]") {
  // The twin differs only in /transport/host. Over replications the poll
  // timer's phase is unrelated to the display's, so the last poll before a
  // render lies u behind it with u uniform on [0, 30 ms): the newest sample
  // the renderer sees is on average 15 ms older (the tracker's own phase adds
  // the same uniform age in both twins). The range of ages widens from one
  // tracker period T to T + 30 ms. The analytic figure integrates over both
  // phases; the simulation averages 20 replications.
  constexpr int kReplications = 20;
  const std::vector<std::string> base = {"/duration_s=3"};
  std::vector<std::string> twin = base;
  twin.push_back("/transport/host=\"interrupt\"");
  std::vector<double> diffs;
  double poll_min = 1e9, poll_max = -1e9, irq_min = 1e9, irq_max = -1e9;
  Json poll_analytic, irq_analytic;
  for (int r = 0; r < kReplications; ++r) {
    const Json poll = run_file("hmd_60hz_serial_poll.json", base, static_cast<uint64_t>(r));
    const Json irq = run_file("hmd_60hz_serial_poll.json", twin, static_cast<uint64_t>(r));
    const Json& pm = poll["figures"]["motion_to_photon_ms"];
    const Json& im = irq["figures"]["motion_to_photon_ms"];
    diffs.push_back(pm["mean"].get<double>() - im["mean"].get<double>());
    poll_min = std::min(poll_min, pm["min"].get<double>());
    poll_max = std::max(poll_max, pm["max"].get<double>());
    irq_min = std::min(irq_min, im["min"].get<double>());
    irq_max = std::max(irq_max, im["max"].get<double>());
    poll_analytic = poll["figures"]["analytic"];
    irq_analytic = irq["figures"]["analytic"];
  }
  REQUIRE(poll_analytic["link"] == "serial poll");
  REQUIRE(irq_analytic["link"] == "serial interrupt");
  const Json& pa = poll_analytic["motion_to_photon_ms"];
  const Json& ia = irq_analytic["motion_to_photon_ms"];
  const double analytic_mean = pa["mean"].get<double>() - ia["mean"].get<double>();
  const double analytic_spread = (pa["max"].get<double>() - pa["min"].get<double>()) -
                                 (ia["max"].get<double>() - ia["min"].get<double>());
  // The hand derivation above: exactly P/2 and P, up to the phase grid (256 steps of 30 ms).
  CHECK(analytic_mean == Approx(15.0).margin(0.15));
  CHECK(analytic_spread == Approx(30.0).margin(0.3));

  double sum = 0.0, sq = 0.0;
  for (double d : diffs) sum += d;
  const double mean = sum / kReplications;
  for (double d : diffs) sq += (d - mean) * (d - mean);
  const double standard_error = std::sqrt(sq / (kReplications - 1) / kReplications);
  INFO("mean added " << mean << " ms, standard error " << standard_error << " ms, analytic " << analytic_mean);
  CHECK(std::abs(mean - analytic_mean) < 4.0 * standard_error + 0.05);
  // The extremes of 20 replications fall inside the analytic range and reach
  // most of it: within a tenth of the poll interval at either end.
  const double spread = (poll_max - poll_min) - (irq_max - irq_min);
  INFO("spread added " << spread << " ms, analytic " << analytic_spread);
  CHECK(poll_min >= pa["min"].get<double>() - 1e-6);
  CHECK(poll_max <= pa["max"].get<double>() + 1e-6);
  CHECK(spread == Approx(analytic_spread).margin(3.0));
}

TEST_CASE("phase luck: commensurate clocks with drawn phases are warned of, with the spread replications show", "[clocks]") {
  // hmd_60hz_direct: a 60 Hz tracker and a 60 Hz display. T_display /
  // T_tracker = 1: every refresh finds the tracker at the same phase, drawn per
  // replication uniformly over 16.667 ms, so a run's mean latency is one draw
  // from a 16.667 ms range. 16 replications: their means lie within that
  // range, and (16 uniform draws) spread over more than half of it unless all
  // 16 fall in one half, which has probability 2 x 2^-16.
  const auto warned = [](const Json& s) {
    for (const auto& w : s["warnings"])
      if (w.get<std::string>().rfind("phase luck:", 0) == 0) return true;
    return false;
  };
  double lo = 1e9, hi = -1e9;
  for (uint64_t r = 0; r < 16; ++r) {
    const Json s = run_file("hmd_60hz_direct.json", {"/duration_s=1"}, r);
    CHECK(warned(s));
    const double mean = s["figures"]["motion_to_photon_ms"]["mean"].get<double>();
    lo = std::min(lo, mean);
    hi = std::max(hi, mean);
  }
  CHECK(hi - lo <= 1000.0 / 60.0 + 1e-6);
  CHECK(hi - lo > 1000.0 / 60.0 / 2);
  const Json first = run_file("hmd_60hz_direct.json", {"/duration_s=1"}, 0);
  CHECK_THAT(first["warnings"][0].get<std::string>(), Catch::Contains("one of 1 phase for the whole run"));
  CHECK_THAT(first["warnings"][0].get<std::string>(), Catch::Contains("up to 16.7 ms"));
  // Fixed phases are the user's choice; 59.94 Hz against 60 Hz meets the
  // tracker in 1000 phases 16.7 us apart (1001/1000 in lowest terms); a
  // 100 ppm tracker drifts through every phase: no luck to speak of.
  CHECK_FALSE(warned(run_file("hmd_60hz_direct.json", {"/duration_s=1", "/tracker/phase_ms=3", "/display/phase_ms=0"}, 0)));
  CHECK_FALSE(warned(run_file("hmd_60hz_direct.json", {"/duration_s=1", "/display/refresh_hz=\"60000/1001\""}, 0)));
  CHECK_FALSE(warned(run_file("hmd_60hz_direct.json", {"/duration_s=1", "/tracker/rate_error_ppm=100"}, 0)));
  // 90 Hz display, 60 Hz tracker: 2/3 in lowest terms, 3 phases 5.56 ms apart.
  const Json ninety = run_file("hmd_60hz_direct.json", {"/duration_s=1", "/display/refresh_hz=90"}, 0);
  REQUIRE(warned(ninety));
  std::string text;
  for (const auto& w : ninety["warnings"])
    if (w.get<std::string>().rfind("phase luck:", 0) == 0) text = w.get<std::string>();
  CHECK_THAT(text, Catch::Contains("one of 3 phases"));
  CHECK_THAT(text, Catch::Contains("up to 5.56 ms"));
}
