// Analytic checks of the conventional pipeline: each test states the value
// the model must produce and why, then runs the simulation.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "latsim/display/raster_timing.hpp"
#include "run_helpers.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using latsim::testing::base_scenario;
using latsim::testing::fig;
using latsim::testing::run;
using Json = nlohmann::json;

namespace {

latsim::display::RasterTiming timing_60hz() {
  latsim::display::RasterParams p;
  p.field_period = latsim::des::RationalSeconds{1, 60};
  return latsim::display::RasterTiming(p);
}

}  // namespace

TEST_CASE("a still head has zero registration error whatever the latency", "[double_buffer]") {
  Json s = base_scenario();
  s["motion"] = {{"type", "still"}};
  s["transport"] = {{"type", "serial"}, {"record_bytes", 32}, {"baud", 9600}, {"host", "poll"}, {"poll_interval_ms", 30}};
  s["pipeline"]["render"]["fixed_ms"] = 40;
  const Json out = run(s);
  CHECK(fig(out, "motion_to_photon_ms")["mean"].get<double>() > 50.0);  // plenty of latency
  REQUIRE(fig(out, "registration_error_arcmin")["count"].get<int64_t>() > 100);
  CHECK(fig(out, "registration_error_arcmin")["max"].get<double>() < 1e-6);
  CHECK(fig(out, "registration_error_px")["max"].get<double>() < 1e-6);
}

TEST_CASE("direct tracker and instant rendering: latency is one field plus each line's scanout delay",
          "[double_buffer]") {
  // The sample taken at retrace k is rendered at once and swapped in at
  // retrace k+1, so every line of field k+1 is exactly one field plus its own
  // scanout delay old.
  const Json out = run(base_scenario());
  const auto t = timing_60hz();
  const double field_ms = t.field_period_ms();
  const double first_line_ms = (t.line_time(1, 0) - t.field_start(1)).to_ms();
  const double last_line_ms = (t.line_time(1, t.lines_per_field() - 1) - t.field_start(1)).to_ms();
  const auto& mtp = fig(out, "motion_to_photon_ms");
  CHECK(mtp["min"].get<double>() == Approx(field_ms + first_line_ms).margin(1e-6));
  CHECK(mtp["max"].get<double>() == Approx(field_ms + last_line_ms).margin(1e-6));
  const auto& disp = fig(out, "display_ms");
  CHECK(mtp["max"].get<double>() - mtp["min"].get<double>() ==
        Approx(disp["max"].get<double>() - disp["min"].get<double>()).margin(1e-6));
  CHECK(fig(out, "image_age_ms")["min"].get<double>() == Approx(field_ms + first_line_ms).margin(1e-6));
  CHECK(fig(out, "image_age_ms")["max"].get<double>() == Approx(field_ms + first_line_ms).margin(1e-6));
  CHECK(fig(out, "frame_rate_hz").get<double>() == Approx(60.0).epsilon(0.02));
}

TEST_CASE("serial polling at P adds a delay uniform on between 0 and P", "[double_buffer][transport]") {
  Json s = base_scenario();
  s["duration_s"] = 60;
  s["tracker"]["rate_hz"] = "60000/1001";  // incommensurate with the 30 ms poll
  s["transport"] = {{"type", "serial"}, {"record_bytes", 32}, {"baud", 19200}, {"host", "poll"}, {"poll_interval_ms", 30}};
  s["display"]["height_px"] = 8;  // the display does not matter here: keep it cheap
  const Json out = run(s);
  const double transmit_ms = 32 * 10 / 19200.0 * 1e3;
  const auto& d = fig(out, "tracker_to_host_ms");
  REQUIRE(d["count"].get<int64_t>() > 3000);
  CHECK(d["min"].get<double>() >= transmit_ms - 1e-9);
  CHECK(d["max"].get<double>() < transmit_ms + 30.0);
  CHECK(d["mean"].get<double>() == Approx(transmit_ms + 15.0).margin(0.5));
  // A uniform distribution on [0, 30) has standard deviation 30/sqrt(12).
  CHECK(d["stddev"].get<double>() == Approx(30.0 / std::sqrt(12.0)).epsilon(0.05));
}

TEST_CASE("interrupt per character removes the poll wait", "[double_buffer][transport]") {
  Json s = base_scenario();
  s["transport"] = {{"type", "serial"}, {"record_bytes", 32}, {"baud", 19200}, {"host", "interrupt"}};
  s["display"]["height_px"] = 8;
  const Json out = run(s);
  const double transmit_ms = 32 * 10 / 19200.0 * 1e3;
  CHECK(fig(out, "tracker_to_host_ms")["max"].get<double>() == Approx(transmit_ms).margin(1e-6));
}

TEST_CASE("double buffering at update interval T shows images aged T to 2T plus scanout", "[double_buffer]") {
  Json s = base_scenario();
  s["duration_s"] = 5;
  s["tracker"]["rate_hz"] = 1000;                // input at most 1 ms stale
  s["pipeline"]["render"]["fixed_ms"] = 25;      // 1.5 fields: a new image every T = 2 fields
  const Json out = run(s);
  const auto t = timing_60hz();
  const double T = 2 * t.field_period_ms();
  const double vblank_ms = (t.line_time(1, 0) - t.field_start(1)).to_ms();
  CHECK(fig(out, "frame_rate_hz").get<double>() == Approx(30.0).epsilon(0.02));
  const auto& age = fig(out, "image_age_ms");
  CHECK(age["min"].get<double>() >= T + vblank_ms - 1e-6);
  CHECK(age["max"].get<double>() <= 1.5 * T + vblank_ms + 1.0 + 1e-6);
  const auto& mtp = fig(out, "motion_to_photon_ms");
  CHECK(mtp["min"].get<double>() >= T - 1e-6);
  CHECK(mtp["max"].get<double>() <= 2 * T + t.field_period_ms() + 1.0);
  CHECK(fig(out, "missed_refreshes").get<int64_t>() > 0);
}

TEST_CASE("constant yaw rate w gives registration error w times latency", "[double_buffer][registration]") {
  // Probes on the horizon are drawn on the centre row; with the aligned
  // tracker and instant rendering their latency is one field plus the centre
  // row's scanout delay, so the error is w times that.
  Json s = base_scenario();
  const double w_deg_s = 30.0;
  Json ring = Json::array();
  for (int i = 0; i < 36; ++i) {
    const double a = units::deg_to_rad(i * 10.0);
    ring.push_back({-2.0 * std::sin(a), 0.0, -2.0 * std::cos(a)});
  }
  s["probes"] = {{"points_m", ring}};
  const Json out = run(s);
  const auto t = timing_60hz();
  const double latency_s = (t.field_period_ms() + (t.line_time(1, 240) - t.field_start(1)).to_ms()) * 1e-3;
  const double expected_arcmin = w_deg_s * latency_s * 60.0;
  const auto& e = fig(out, "registration_error_arcmin");
  REQUIRE(e["count"].get<int64_t>() > 50);
  CHECK(e["mean"].get<double>() == Approx(expected_arcmin).epsilon(0.01));
  CHECK(e["min"].get<double>() == Approx(expected_arcmin).epsilon(0.01));
  CHECK(e["max"].get<double>() == Approx(expected_arcmin).epsilon(0.01));
}

TEST_CASE("rendering ahead with queued frames costs latency", "[double_buffer]") {
  Json s = base_scenario();
  s["pipeline"]["render"]["fixed_ms"] = 5;
  const double plain = fig(run(s), "motion_to_photon_ms")["mean"].get<double>();
  s["pipeline"]["queued_frames"] = 2;
  const double ahead = fig(run(s), "motion_to_photon_ms")["mean"].get<double>();
  // Two more queued frames: two more refreshes of waiting.
  CHECK(ahead - plain == Approx(2 * 1000.0 / 60.0).margin(0.5));
}

TEST_CASE("without vsync a new image replaces the front buffer mid-scan and lowers latency", "[double_buffer]") {
  Json s = base_scenario();
  s["pipeline"]["render"]["fixed_ms"] = 5;
  s["display"]["scanout"] = "line";
  const double vsync = fig(run(s), "motion_to_photon_ms")["mean"].get<double>();
  s["pipeline"]["vsync"] = false;
  const Json torn = run(s);
  CHECK(fig(torn, "motion_to_photon_ms")["mean"].get<double>() < vsync - 5.0);
  CHECK(fig(torn, "frame_rate_hz").get<double>() > 150.0);
}

TEST_CASE("same scenario and seed give identical figures, another seed with jitter differs", "[double_buffer][determinism]") {
  Json s = base_scenario();
  s["tracker"]["jitter_ms"] = 2;
  s["pipeline"]["render"] = {{"fixed_ms", 5}, {"variation", "normal"}, {"variation_fraction", 0.2}};
  const Json a = run(s), b = run(s);
  CHECK(a["figures"].dump() == b["figures"].dump());
  CHECK(a["fingerprint"] == b["fingerprint"]);
  s["seed"] = 8;
  const Json c = run(s);
  CHECK(a["fingerprint"] != c["fingerprint"]);
}

TEST_CASE("hours of simulated time at 59.94 Hz stay exact", "[double_buffer][long_time]") {
  // With the tracker locked to the 60000/1001 Hz refresh, latency per line is
  // the same in the third hour as in the first second: no drift, no rounding creep.
  Json s = base_scenario();
  s["tracker"]["rate_hz"] = "60000/1001";
  s["display"]["refresh_hz"] = "60000/1001";
  s["display"]["height_px"] = 4;
  s["display"]["vblank_lines"] = 1;
  s["probes"] = {{"points_m", Json::array({{0.0, 0.0, -2.0}})}};
  s["duration_s"] = 1;
  const Json short_run = run(s);
  s["duration_s"] = 3 * 3600;
  const Json long_run = run(s);
  const auto& a = fig(short_run, "motion_to_photon_ms");
  const auto& b = fig(long_run, "motion_to_photon_ms");
  CHECK(b["min"].get<double>() == a["min"].get<double>());
  CHECK(b["max"].get<double>() == a["max"].get<double>());
  CHECK(std::isfinite(fig(long_run, "registration_error_arcmin")["max"].get<double>()));
  CHECK(fig(long_run, "fields").get<int64_t>() == 647353);  // retraces k with k·1001/60000 s < 10800 s: k = 0 … 647352
}

TEST_CASE("the analytic phase enumeration agrees with the simulation", "[double_buffer][analytic]") {
  struct Case {
    const char* name;
    Json tracker_rate, refresh;
    Json transport;
    double render_ms;
  };
  const Case cases[] = {
      {"aligned direct", 60, 60, Json{{"type", "direct"}}, 0.0},
      {"59.94 Hz display, 60 Hz tracker", 60, "60000/1001", Json{{"type", "direct"}}, 5.0},
      {"serial poll 30 ms", 60, 60,
       Json{{"type", "serial"}, {"record_bytes", 24}, {"baud", 38400}, {"host", "poll"}, {"poll_interval_ms", 30},
            {"poll_phase_ms", 7}},
       20.0},
      {"serial interrupt, 59.94 Hz tracker", "60000/1001", 60,
       Json{{"type", "serial"}, {"record_bytes", 24}, {"baud", 38400}, {"host", "interrupt"}}, 12.0},
  };
  for (const auto& c : cases) {
    SECTION(c.name) {
      Json s = base_scenario();
      s["duration_s"] = 20;
      // Fixed phases: the enumeration covers exactly the phases this run takes.
      s["tracker"] = {{"rate_hz", c.tracker_rate}, {"internal_delay_ms", 1.5}, {"phase_ms", 0.25}};
      s["display"]["refresh_hz"] = c.refresh;
      s["display"]["height_px"] = 32;
      s["transport"] = c.transport;
      s["pipeline"]["render"]["fixed_ms"] = c.render_ms;
      const Json out = run(s);
      REQUIRE(out["figures"].contains("analytic"));
      const auto& a = out["figures"]["analytic"];
      REQUIRE(a["hyperperiod_s"].get<double>() <= 20.0);
      const auto& sim = fig(out, "motion_to_photon_ms");
      CHECK(sim["min"].get<double>() == Approx(a["motion_to_photon_ms"]["min"].get<double>()).margin(1e-6));
      CHECK(sim["max"].get<double>() == Approx(a["motion_to_photon_ms"]["max"].get<double>()).margin(1e-6));
      CHECK(sim["mean"].get<double>() == Approx(a["motion_to_photon_ms"]["mean"].get<double>()).epsilon(0.01));
    }
  }
}

TEST_CASE("the analytic mean over one repeat cycle matches a hand derivation at 90, 75, 60 and 59.94 Hz",
          "[double_buffer][analytic]") {
  // Direct link, tracker at 60 Hz (T = 16.667 ms) with internal delay d = 1.5
  // ms, display phase 0, instant rendering: the frame rendered at retrace t_s
  // uses the newest sample t_k with t_k + d <= t_s and is shown through the
  // next field. A display of 2 lines without blanking lights its lines at 0
  // and F/2 after the retrace, so the mean latency per line is
  //   F (one field) + F/4 (mean line offset) + mean over the cycle of (t_s - t_k).
  // The repeat cycle holds exactly lcm(F, T)/F frames; one too many biases it.
  struct Case {
    const char* name;
    Json refresh;
    double tracker_phase_ms;
    double expected_mean_ms;
  };
  const Case cases[] = {
      // 90 Hz: F = 11.111 ms, cycle 1/30 s = 3 fields, retraces at 0, 11.111, 22.222 ms
      // against samples at 0 and 16.667 ms (ready 1.5 and 18.167): ages 16.667,
      // 11.111, 5.556 ms, mean 11.111 ms. 11.111 + 2.778 + 11.111 = 25.0 ms.
      {"90 Hz", 90, 0.0, 25.0},
      // 75 Hz: F = 13.333 ms, cycle 1/15 s = 5 fields: retraces at 0, 13.333,
      // 26.667, 40, 53.333 ms against samples at 0, 16.667, 33.333, 50 ms: ages
      // 16.667, 13.333, 10, 6.667, 3.333 ms, mean 10 ms. 13.333 + 3.333 + 10 = 26.667 ms.
      {"75 Hz", 75, 0.0, 13.0 + 1.0 / 3.0 + 10.0 / 3.0 + 10.0},
      // 60 Hz, tracker phase 10 ms: every retrace (at k·16.667 ms) sees the sample
      // measured 6.667 ms earlier (ready 5.167 ms earlier). 16.667 + 4.167 + 6.667 = 27.5 ms.
      {"60 Hz", 60, 10.0, 27.5},
      // 59.94 Hz: F = 1001/60 ms, cycle 1000 fields = 1001 samples. Retrace s lies
      // u_s = s/60 ms after sample s (s = 0 … 999); that sample is ready when
      // u_s >= 1.5 ms (s >= 90), otherwise the one before serves (age u_s + T).
      // Sum of ages = Σ s/60 + 90·T = (499500 + 90000)/60 ms = 9825 ms, mean 9.825 ms.
      // 1001/60 · 1.25 + 9.825 = 20.854167 + 9.825 = 30.679167 ms.
      {"59.94 Hz", "60000/1001", 0.0, 1001.0 / 60.0 * 1.25 + 9.825},
  };
  for (const auto& c : cases) {
    SECTION(c.name) {
      Json s = base_scenario();
      s["duration_s"] = 3;
      s["tracker"] = {{"rate_hz", 60}, {"internal_delay_ms", 1.5}, {"phase_ms", c.tracker_phase_ms}};
      s["display"]["refresh_hz"] = c.refresh;
      s["display"]["height_px"] = 2;
      s["display"]["vblank_lines"] = 0;
      s["display"]["hblank_px"] = 0;
      const Json out = run(s);
      REQUIRE(out["figures"].contains("analytic"));
      const auto& a = out["figures"]["analytic"];
      CHECK(a["motion_to_photon_ms"]["mean"].get<double>() == Approx(c.expected_mean_ms).margin(1e-6));
    }
  }
}

TEST_CASE("no analytic figure where the configuration is not tractable", "[double_buffer][analytic]") {
  Json s = base_scenario();
  s["tracker"]["jitter_ms"] = 1;
  CHECK_FALSE(run(s)["figures"].contains("analytic"));
}

TEST_CASE("the analytic figure lights each line as the display's persistence does", "[double_buffer][analytic]") {
  // The 60 Hz case above (F = 16.667 ms, 2 lines without blanking, every
  // retrace sees a sample 6.667 ms old): 27.5 ms per line on average, the
  // lines lit at 0 and F/2 after the retrace. With persistence each line's
  // photon is the middle of its lit interval (response r = 0.1 ms, flash 2 ms):
  //   full:    + r/2 + F/2 (held a whole field)    27.5 + 0.05 + 8.333 = 35.883 ms
  //   rolling: + r + 1                             27.5 + 1.1 = 28.6 ms
  //   global:  every line at F + r + 1 after its retrace (after the field's
  //            last line) instead of F/4 on average: 27.5 - 4.167 + 17.767 = 41.1 ms,
  //            the same for every line and frame, so min = mean = max.
  struct Case {
    const char* name;
    Json persistence;
    double expected_mean_ms;
  };
  const double f = 1000.0 / 60.0;
  const Case cases[] = {
      {"full", {{"type", "full"}, {"response_ms", 0.1}}, 27.5 + 0.05 + f / 2},
      {"rolling", {{"type", "rolling"}, {"lit_ms", 2}, {"response_ms", 0.1}}, 27.5 + 1.1},
      {"global", {{"type", "global"}, {"lit_ms", 2}, {"response_ms", 0.1}}, 27.5 - f / 4 + f + 1.1},
  };
  for (const auto& c : cases) {
    SECTION(c.name) {
      Json s = base_scenario();
      s["duration_s"] = 3;
      s["tracker"] = {{"rate_hz", 60}, {"internal_delay_ms", 1.5}, {"phase_ms", 10}};
      s["display"]["height_px"] = 2;
      s["display"]["vblank_lines"] = 0;
      s["display"]["hblank_px"] = 0;
      s["display"]["persistence"] = c.persistence;
      const Json out = run(s);
      REQUIRE(out["figures"].contains("analytic"));
      const auto& a = out["figures"]["analytic"]["motion_to_photon_ms"];
      CHECK(a["mean"].get<double>() == Approx(c.expected_mean_ms).margin(1e-6));
      if (std::string(c.name) == "global") CHECK(a["min"].get<double>() == Approx(a["max"].get<double>()).margin(1e-6));
      // And the simulation, measuring at the same instants, agrees.
      CHECK(fig(out, "motion_to_photon_ms")["mean"].get<double>() == Approx(c.expected_mean_ms).margin(1e-3));
    }
  }
}
