// The render cost's random variation: independent normal factors are the
// stream's own normal draws, and correlated ones are a first-order
// autoregression whose statistics are derived below.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "latsim/des/random.hpp"
#include "latsim/renderer/render_cost.hpp"

using latsim::des::RandomStream;
using latsim::renderer::RenderCost;

namespace {

RenderCost normal_cost(double fraction, double correlation_frames) {
  RenderCost::Params p;
  p.fixed_ms = 10.0;
  p.variation = RenderCost::Variation::Normal;
  p.variation_fraction = fraction;
  p.variation_correlation_frames = correlation_frames;
  return RenderCost(p, 0, 0);
}

/// The factors of n frames: each frame's time over the nominal 10 ms.
std::vector<double> factors(RenderCost cost, int n, RandomStream& stream) {
  std::vector<double> f;
  for (int j = 0; j < n; ++j) f.push_back(cost.frame_time(stream).to_ms() / 10.0);
  return f;
}

double autocorrelation(const std::vector<double>& x, size_t lag) {
  double mean = 0.0;
  for (double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < x.size(); ++i) {
    den += (x[i] - mean) * (x[i] - mean);
    if (i + lag < x.size()) num += (x[i] - mean) * (x[i + lag] - mean);
  }
  return num / den;
}

}  // namespace

TEST_CASE("render cost: independent normal factors are 1 + the stream's normal draws") {
  // A second method: the same stream drawn by hand.
  RandomStream a(7, "cost"), b(7, "cost");
  RenderCost cost = normal_cost(0.1, 0.0);
  for (int j = 0; j < 100; ++j) {
    const double expected = 10.0 * (1.0 + b.normal(0.0, 0.1));
    CHECK(cost.frame_time(a).to_ms() == Approx(expected).epsilon(1e-9));
  }
}

TEST_CASE("render cost: correlated normal factors keep their spread and correlate as exp(-k / N)") {
  // x_j = r x_(j-1) + sqrt(1 - r^2) z_j with x_0 = z_0 has unit variance at
  // every j (r^2 + 1 - r^2 = 1) and correlation r^k between frames k apart,
  // r = exp(-1 / N). N = 10: r = 0.905, frames 10 apart 1/e = 0.368. With
  // 200,000 frames the estimates' standard errors are under 0.01 for the
  // correlations (about sqrt((1 + r^2) / (1 - r^2) / n) at worst, 0.01) and
  // about 1.5 % for the variance (effective n = n (1 - r) / (1 + r) = 10,000).
  RandomStream stream(11, "cost");
  const std::vector<double> f = factors(normal_cost(0.1, 10.0), 200000, stream);
  double mean = 0.0, var = 0.0;
  for (double v : f) mean += v;
  mean /= static_cast<double>(f.size());
  for (double v : f) var += (v - mean) * (v - mean);
  var /= static_cast<double>(f.size());
  CHECK(mean == Approx(1.0).margin(0.005));
  CHECK(std::sqrt(var) == Approx(0.1).epsilon(0.03));
  CHECK(autocorrelation(f, 1) == Approx(std::exp(-0.1)).margin(0.01));
  CHECK(autocorrelation(f, 10) == Approx(std::exp(-1.0)).margin(0.03));
  // Independent draws (N = 0) do not correlate.
  RandomStream other(11, "cost");
  const std::vector<double> g = factors(normal_cost(0.1, 0.0), 200000, other);
  CHECK(autocorrelation(g, 1) == Approx(0.0).margin(0.01));
}

TEST_CASE("render cost: the first correlated factor is the stationary draw itself") {
  // x_0 = z_0: the first frame is drawn as an independent one would be.
  RandomStream a(3, "cost"), b(3, "cost");
  RenderCost correlated = normal_cost(0.2, 50.0), independent = normal_cost(0.2, 0.0);
  CHECK(correlated.frame_time(a).to_ms() == Approx(independent.frame_time(b).to_ms()).epsilon(1e-12));
}
