// Steady state of one axis of a constant-velocity Kalman filter, by the
// scalar 2x2 recursion written out by hand: a second method against which the
// filter's matrix code and its effect in a run are checked.
#pragma once

namespace latsim::testing {

/// The filter's own posterior covariance [[a, b], [b, c]] (angle, rate) and,
/// for a truly still head or a truly constant rate (no process noise), the
/// covariance [[A, B], [B, C]] of the actual error under the filter's gains.
struct ScalarSteadyState {
  double a = 0, b = 0, c = 0;
  double A = 0, B = 0, C = 0;
  /// Variance of the actual error extrapolated h seconds at the estimated rate.
  double actual_at(double h) const { return A + 2 * h * B + h * h * C; }
};

/// `steps` updates dt apart with process noise density s and measurement
/// variance r, from the prior [[r, 0], [0, prior_c]].
inline ScalarSteadyState scalar_steady_state(double r, double s, double dt, double prior_c, int steps) {
  ScalarSteadyState x{r, 0.0, prior_c, r, 0.0, 0.0};
  for (int i = 0; i < steps; ++i) {
    x.a += 2 * dt * x.b + dt * dt * x.c + s * dt * dt * dt / 3;
    x.b += dt * x.c + s * dt * dt / 2;
    x.c += s * dt;
    const double A = x.A + 2 * dt * x.B + dt * dt * x.C, B = x.B + dt * x.C, C = x.C;
    const double k0 = x.a / (x.a + r), k1 = x.b / (x.a + r);
    x.c -= k1 * x.b;
    x.b *= 1 - k0;
    x.a *= 1 - k0;
    // Actual error e' = (I - K H) e + K n, e = [angle, rate].
    x.A = (1 - k0) * (1 - k0) * A + k0 * k0 * r;
    x.B = (1 - k0) * (B - k1 * A) + k0 * k1 * r;
    x.C = k1 * k1 * A - 2 * k1 * B + C + k1 * k1 * r;
  }
  return x;
}

}  // namespace latsim::testing
