// The Kalman filter on a noisy still head: steadier than the raw samples,
// by exactly as much as the filter's steady state says.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "../models/tracker/kalman_steady_state.hpp"
#include "run_helpers.hpp"
#include "latsim/units/units.hpp"

namespace units = latsim::units;

using latsim::testing::fig;
using latsim::testing::run;
using latsim::testing::scalar_steady_state;
using Json = nlohmann::json;

namespace {

constexpr double kNoiseDeg = 0.2;   // tracker orientation noise, per axis
constexpr double kPsdDeg = 50.0;    // the filter's default process noise

Json still_head(int tracker_hz, const Json& prediction) {
  return {{"duration_s", 30},
          {"seed", 5},
          {"motion", {{"type", "still"}, {"position_m", {0, 1.6, 0}}}},
          {"tracker", {{"rate_hz", tracker_hz}, {"internal_delay_ms", 2}, {"noise", {{"orientation_stddev_deg", kNoiseDeg}}}}},
          {"host", {{"stereo", false}, {"prediction", prediction}}},
          {"display", {{"refresh_hz", 60}, {"width_px", 640}, {"height_px", 480}, {"hfov_deg", 60}, {"scanout", "field"}}},
          {"probes", {{"points_m", {{0, 1.6, -2}, {0.5, 1.6, -2}, {-0.5, 1.6, -2}}}}},
          {"pipeline", {{"type", "double_buffer"}, {"render", {{"fixed_ms", 8}}}}}};
}

struct Jitter {
  double mean_arcmin, stddev_arcmin, horizon_s;
};

Jitter registration(const Json& scenario) {
  const Json out = run(scenario);
  const Json& reg = fig(out, "registration_error_arcmin");
  return {reg.at("mean").get<double>(), reg.at("stddev").get<double>(),
          fig(out, "prediction_horizon_ms").at("mean").get<double>() * 1e-3};
}

/// A probe ahead of the eye is displaced by the two components of the
/// orientation error across its direction, each normal with the same
/// standard deviation, so its registration error is Rayleigh distributed
/// and its mean and spread both scale with that deviation: the ratio of
/// filtered to raw registration error is the ratio of the filter's actual
/// error deviation to the tracker's.
double expected_ratio(int tracker_hz, double horizon_s) {
  const double r = std::pow(units::deg_to_rad(kNoiseDeg), 2), s = std::pow(units::deg_to_rad(kPsdDeg), 2);
  const auto ss = scalar_steady_state(r, s, 1.0 / tracker_hz, std::pow(units::deg_to_rad(100.0), 2), 20000);
  return std::sqrt(ss.actual_at(horizon_s) / r);
}

}  // namespace

TEST_CASE("the Kalman filter holds a noisy still head steadier than the raw samples", "[prediction][kalman]") {
  const Jitter raw = registration(still_head(60, {{"type", "none"}}));
  // The raw samples: Rayleigh with the tracker's deviation, mean sigma sqrt(pi/2).
  CHECK(raw.mean_arcmin == Approx(kNoiseDeg * 60.0 * std::sqrt(units::kPi / 2.0)).epsilon(0.05));

  SECTION("filtered to each sample's own instant (horizon 0), 60 Hz tracker") {
    const Jitter kf = registration(still_head(60, {{"type", "kalman"}, {"horizon_ms", 0}}));
    const double ratio = expected_ratio(60, 0.0);
    CHECK(ratio < 0.9);
    CHECK(kf.mean_arcmin / raw.mean_arcmin == Approx(ratio).epsilon(0.05));
    CHECK(kf.stddev_arcmin / raw.stddev_arcmin == Approx(ratio).epsilon(0.08));
  }
  SECTION("predicted to the photon time, 1000 Hz tracker") {
    const Jitter raw_fast = registration(still_head(1000, {{"type", "none"}}));
    const Jitter kf = registration(still_head(1000, {{"type", "kalman"}}));
    const double ratio = expected_ratio(1000, kf.horizon_s);
    CHECK(ratio < 0.8);
    CHECK(kf.mean_arcmin / raw_fast.mean_arcmin == Approx(ratio).epsilon(0.1));
    CHECK(kf.stddev_arcmin < raw_fast.stddev_arcmin);
  }
  SECTION("predicted 40 ms ahead from a 60 Hz tracker, extrapolation amplifies the noise") {
    // The price of prediction: the rate estimate's noise times the horizon.
    const Jitter kf = registration(still_head(60, {{"type", "kalman"}}));
    const double ratio = expected_ratio(60, kf.horizon_s);
    CHECK(ratio > 1.2);
    CHECK(kf.mean_arcmin / raw.mean_arcmin == Approx(ratio).epsilon(0.1));
  }
}
