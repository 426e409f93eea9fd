// Apparent latency on hand-derivable shown traces: a pure delay, a perfect
// predictor, and a constant-velocity predictor at the onset of a
// minimum-jerk movement.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <vector>

#include "latsim/measurement/apparent_latency.hpp"
#include "latsim/tracker/minimum_jerk.hpp"
#include "latsim/units/units.hpp"

using namespace latsim;
using latsim::des::Time;
using measurement::ShownSample;

namespace {


// Impulses (lit for no time) every `period` from 0 to `end`, each showing the
// orientation `shown(photon)`.
std::vector<ShownSample> impulses(Time period, Time end, const std::function<glm::dquat(Time)>& shown) {
  std::vector<ShownSample> out;
  for (int64_t i = 0; period * i <= end; ++i) out.push_back(ShownSample{period * i, Time::zero(), shown(period * i)});
  return out;
}

glm::dquat yaw(double deg) { return tracker::quat_from_rotation_vector(glm::dvec3(0.0, deg * units::kRadPerDeg, 0.0)); }

}  // namespace

TEST_CASE("a pure delay of d ms has an apparent latency of d ms", "[apparent_latency]") {
  // Every refresh (90 Hz, impulses) shows the true orientation of d = 23.4 ms
  // before: misfit(s) = Σ (ω (s − d))², a parabola with its vertex at d.
  const tracker::ConstantAngularVelocity truth(tracker::Pose{}, {0, 1, 0}, 100.0);
  const Time d = Time::us(23'400);
  const auto shown = impulses(Time::ps(11'111'111'111), Time::s(2),
                              [&](Time t) { return truth.pose_at(t - d).orientation; });
  const std::span<const ShownSample> window(shown.data() + 40, 9);
  const auto fit = measurement::fit_shift_ms(window, truth, Time::ms(150));
  REQUIRE(fit.has_value());
  CHECK(*fit == Approx(23.4).margin(1e-6));
  // The sliding windows: the motion is steady from time zero, every window says d.
  tracker::MotionPhaseClassifier phases(truth, tracker::MotionPhaseParams{});
  const auto r = measurement::apparent_latency(shown, truth, phases, measurement::ApparentLatencyParams{});
  REQUIRE(r.windows.size() > 150);
  for (const auto& w : r.windows) CHECK(w.shift_ms == Approx(23.4).margin(1e-6));
  REQUIRE(r.steady_ms.has_value());
  CHECK(r.unresolved == 0);
}

TEST_CASE("a perfect predictor under constant velocity has no apparent latency", "[apparent_latency]") {
  // Shown = the truth at its own photon time: the misfit vanishes at s = 0.
  const tracker::ConstantAngularVelocity truth(tracker::Pose{}, {0, 1, 0}, 250.0);
  const auto shown = impulses(Time::ps(8'333'333'333), Time::s(1), [&](Time t) { return truth.pose_at(t).orientation; });
  const auto fit = measurement::fit_shift_ms(std::span(shown.data() + 10, 12), truth, Time::ms(150));
  REQUIRE(fit.has_value());
  CHECK(*fit == Approx(0.0).margin(1e-6));
}

TEST_CASE("a window without movement has no apparent latency", "[apparent_latency]") {
  const tracker::StillMotion truth(tracker::Pose{});
  const auto shown = impulses(Time::ms(10), Time::ms(200), [](Time) { return glm::dquat(1, 0, 0, 0); });
  CHECK_FALSE(measurement::fit_shift_ms(shown, truth, Time::ms(150)).has_value());
}

TEST_CASE("a constant-velocity predictor at the onset of a minimum-jerk movement", "[apparent_latency]") {
  // Truth: a minimum-jerk turn of A = 60 degrees in D = 1 s after a 1 s rest.
  // Near the start (u = t − 1 s, τ = u / D small) x(u) ≈ c u³, c = 10 A / D³.
  // The display shows, with latency L, the constant-velocity extrapolation
  // of the sample taken L before: x̂(u) = x(u − L) + L ẋ(u − L)
  //   = c (u − L)³ + 3 c L (u − L)² = c (u − L)² (u + 2L).
  // The shift s that aligns the two at u solves c (u − s)³ = x̂(u):
  //   s(u) = u − cbrt((u − L)² (u + 2L)).
  // At u = 3L: s = 3L − cbrt(4 L² · 5 L) = (3 − 20^(1/3)) L = 0.28558 L,
  // (for u ≫ L: s ≈ L²/u, prediction catching up), while a pure delay gives L.
  // A short window (5 impulses 1 ms apart around u = 3L) fits that pointwise
  // shift; the quartic term of the profile (−15τ⁴ against 10τ³, relative
  // 1.5τ = 4.5 % at τ = 0.03) moves it by a few per cent of s.
  tracker::MinimumJerkParams mj;
  mj.amplitude_deg = 60.0;
  mj.duration = Time::s(1);
  mj.rest = Time::s(1);
  const tracker::MinimumJerkMotion truth(mj);
  const Time L = Time::ms(10);
  const double a_over_d = 60.0;  // deg/s
  auto predicted_deg = [&](Time t) {
    const Time measured = t - L;
    const double tau = std::clamp((measured - mj.rest).to_seconds() / mj.duration.to_seconds(), 0.0, 1.0);
    const double rate_deg_s = a_over_d * 30.0 * tau * tau * (1.0 - tau) * (1.0 - tau);  // ẋ = (A/D) s'(τ)
    return truth.angle_deg_at(measured) + L.to_seconds() * rate_deg_s;
  };
  const auto shown = impulses(Time::ms(1), Time::ms(2200), [&](Time t) { return yaw(predicted_deg(t)); });
  const Time centre = Time::ms(1030);  // u = 3L
  const std::span<const ShownSample> window(shown.data() + 1028, 5);
  REQUIRE(window.front().photon == Time::ms(1028));
  const auto fit = measurement::fit_shift_ms(window, truth, Time::ms(150));
  REQUIRE(fit.has_value());
  const double hand_ms = (3.0 - std::cbrt(20.0)) * 10.0;  // 2.8558 ms
  CHECK(*fit == Approx(hand_ms).margin(0.05 * hand_ms));
  // The same pointwise shift with the whole quintic, by bisection on
  // x(u − s) = x̂(u) (x falls as s grows). The window's least-squares fit is
  // the mean of s(u) over its refreshes weighted by the speed² ∝ u⁴: the
  // weight's centre lies Δu = Σδ(u+δ)⁴ / Σ(u+δ)⁴ = 0.264 ms after u = 30 ms
  // (δ = −2 … 2 ms) with mean δ² = 2.018 ms², and s'(3L) = 1 − 8 / 20^(2/3)
  // = −0.0858, s''(3L) = 0.0054 /ms, so the fit is s(3L) − 0.0858 · 0.264
  // + 0.0054 · 2.018 / 2 = s(3L) − 0.0172 ms (to first order).
  const double shown_deg = predicted_deg(centre);
  double lo = 0.0, hi = 30.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (truth.angle_deg_at(centre - Time::ps(std::llround(mid * 1e9))) > shown_deg ? lo : hi) = mid;
  }
  CHECK(*fit == Approx(lo - 0.0172).margin(0.005));
  CHECK(lo < hand_ms);  // the quartic term slows the start: the truth is reached a little sooner

  // Over the whole movement: the onset windows lag more than the steady ones,
  // and the catch-up time is reported.
  tracker::MotionPhaseParams phase_params;
  phase_params.threshold_deg_s = 20.0;
  tracker::MotionPhaseClassifier phases(truth, phase_params);
  const auto r = measurement::apparent_latency(shown, truth, phases, measurement::ApparentLatencyParams{});
  double onset = 0.0, steady = 0.0;
  int n_onset = 0, n_steady = 0;
  for (const auto& w : r.windows) {
    if (w.phase == tracker::MotionPhase::Onset) onset += w.shift_ms, ++n_onset;
    if (w.phase == tracker::MotionPhase::Steady) steady += w.shift_ms, ++n_steady;
  }
  REQUIRE(n_onset > 0);
  REQUIRE(n_steady > 0);
  CHECK(onset / n_onset > steady / n_steady);
  // Mid-movement x̂ = x(t − L) + L ẋ(t − L) ≈ x(t) − (L²/2) ẍ: a shift of
  // (L²/2) ẍ/ẋ = (L²/2) (2/τ − 2/(1 − τ)) / D, at most 0.00005 s² · 6.5 /s
  // = 0.33 ms where steady motion begins (τ ≈ 0.22 at 20 deg/s), of either sign.
  CHECK(std::abs(steady / n_steady) < 0.5);
  REQUIRE(r.catch_up_ms.size() + static_cast<size_t>(r.never_caught_up) == 1);
}

TEST_CASE("a controller is seen through the head's error", "[controller]") {
  // Hand derivation with yaws about +y (rotations about one axis add): an
  // image shown with the head at 0° draws the controller at 30°, i.e. 30° to
  // the left in the view; the viewer's head is truly at 10°, so the view's
  // 30° lies at 40° in the world.
  using latsim::measurement::controller_seen;
  const glm::dquat seen = controller_seen(yaw(10.0), yaw(0.0), yaw(30.0));
  CHECK(latsim::measurement::twist_deg(yaw(0.0), seen, glm::dvec3(0.0, 1.0, 0.0)) == Approx(40.0).margin(1e-9));
  // A shown head equal to the true one leaves the drawn pose as it is.
  const glm::dquat drawn = glm::normalize(glm::dquat(0.9, 0.1, -0.3, 0.2));
  const glm::dquat h = glm::normalize(glm::dquat(0.5, 0.5, 0.1, -0.2));
  CHECK(latsim::tracker::angle_between(controller_seen(h, h, drawn), drawn) == Approx(0.0).margin(1e-12));
}

TEST_CASE("the start of a shown movement lags the start of the true one by the delay, predicted or not",
          "[apparent_latency]") {
  // A snap: 30 degrees of minimum-jerk turn in 20 ms after 0.2 s of rest,
  // so x(u) = 30 (10 s^3 - ...) with s = u / 20 ms, and x reaches the 0.05
  // degree threshold at u0 = 20 ms (0.05 / 300)^(1/3) = 1.10 ms (the
  // higher powers change it by under 1 %). A display showing the truth
  // d = 25 ms late, refreshed every 1 ms, first shows it past the threshold
  // at the first refresh at or after u0 + d: the start latency is d + [0, 1) ms.
  tracker::MinimumJerkParams mj;
  mj.amplitude_deg = 30.0;
  mj.duration = Time::ms(20);
  mj.rest = Time::ms(200);
  const tracker::MinimumJerkMotion truth(mj);
  const Time d = Time::ms(25);
  const auto delayed = impulses(Time::ms(1), Time::ms(400), [&](Time t) { return truth.pose_at(t - d).orientation; });
  const auto plain = measurement::start_latency_ms(delayed, truth, Time::ms(200), Time::ms(400), 0.05);
  REQUIRE(plain.has_value());
  CHECK(*plain >= 25.0);
  CHECK(*plain < 26.0);
  // Constant-velocity prediction over d from samples 1 ms apart: the shown
  // angle is x(t - d) + d (x(t - d) - x(t - d - 1 ms)) / 1 ms. Before the
  // movement has reached the sample at t - d it shows the rest; the first
  // sample inside it, at t - d = u >= 0, shows at most x(u) (1 + 25), which
  // passes 0.05 degree once x(u) > 0.05 / 26, at u = u0 / 26^(1/3) = 0.37
  // ms: prediction moves the shown start by at most u0 (1.1 ms) earlier, no
  // more, because no sample before the movement holds it.
  const auto predicted = impulses(Time::ms(1), Time::ms(400), [&](Time t) {
    const Time m = t - d;
    const glm::dquat q1 = truth.pose_at(m).orientation, q0 = truth.pose_at(m - Time::ms(1)).orientation;
    const glm::dvec3 w = tracker::rotation_vector_between(q0, q1) / 1e-3;
    return tracker::quat_from_rotation_vector(w * d.to_seconds()) * q1;
  });
  const auto fast = measurement::start_latency_ms(predicted, truth, Time::ms(200), Time::ms(400), 0.05);
  REQUIRE(fast.has_value());
  CHECK(*fast >= 25.0 - 1.1);
  CHECK(*fast <= 25.0);
}
