// What the host's predictor knows of sample times (/host/prediction/knowledge):
// the true measurement instant (oracle) or only its own clock (runtime).
#include <catch2/catch.hpp>

#include <algorithm>

#include "run_helpers.hpp"
#include "steady_samples.hpp"

using latsim::testing::base_scenario;
using latsim::testing::fig;
using latsim::testing::run;
using Json = nlohmann::json;

namespace {

Json with_knowledge(Json s, const char* knowledge) {
  s["host"] = {{"prediction", {{"type", "constant_velocity"}, {"knowledge", knowledge}}}};
  return s;
}

}  // namespace

TEST_CASE("on a direct link a runtime host knows every sample time exactly", "[prediction][knowledge]") {
  // The record is visible the instant it is ready, its measurement plus the
  // tracker's internal delay; the runtime host subtracts that configured
  // delay (and no time on the link): its stamp is the measurement itself.
  Json s = base_scenario();  // constant 30 deg/s yaw
  s["tracker"]["internal_delay_ms"] = 2;
  const Json oracle = run(with_knowledge(s, "oracle"));
  const Json runtime = run(with_knowledge(s, "runtime"));
  CHECK(oracle.at("figures") == runtime.at("figures"));
}

TEST_CASE("a runtime host does not know an interrupt handler's time, and predicts that much short",
          "[prediction][knowledge]") {
  // A 115200 baud line, 32 bytes of 10 bits: 86.8 us a character; each
  // character's interrupt handler takes 50 us, done before the next one
  // arrives, so every record is visible 50 us after its last character.
  // The runtime host stamps it at visible - transmit time - internal delay
  // = measurement + 50 us, the same offset for every record: the stamped
  // intervals are the true ones and the constant-velocity rate is exact,
  // but every prediction starts 50 us late from the sample's pose and falls
  // short by rate x 50 us = 30 deg/s x 50e-6 s = 0.0015 degrees. The
  // oracle host predicts exactly.
  Json s = base_scenario();
  s["transport"] = {{"type", "serial"}, {"record_bytes", 32}, {"baud", 115200}, {"host", "interrupt"},
                    {"per_char_interrupt_us", 50}};
  auto steady = [](const Json& scenario) {
    return latsim::testing::steady_samples(
        latsim::scenario::ScenarioDocument::from_json(scenario, LATSIM_SOURCE_DIR "/scenarios"), 500.0);
  };
  const auto [oracle, oracle_after] = steady(with_knowledge(s, "oracle"));
  const auto [runtime, runtime_after] = steady(with_knowledge(s, "runtime"));
  // After half a second (the first images hold a pose until the predictor
  // has two samples): every image is off by the same angle.
  const std::vector<double>& e = runtime_after.at("prediction_error_deg");
  REQUIRE(e.size() > 50);
  CHECK(*std::max_element(e.begin(), e.end()) == Approx(0.0015).epsilon(1e-6));
  CHECK(*std::min_element(e.begin(), e.end()) == Approx(0.0015).epsilon(1e-6));
  CHECK(latsim::testing::max_of(oracle_after.at("prediction_error_deg")) < 1e-9);
  // Latency and the horizon keep the true measurement as their origin.
  CHECK(fig(oracle, "prediction_horizon_ms") == fig(runtime, "prediction_horizon_ms"));
  CHECK(fig(oracle, "motion_to_photon_ms") == fig(runtime, "motion_to_photon_ms"));
}
