// Replaying a column: in order (wrap, stop), scale and offset, clipping, and
// the circular moving-block bootstrap's mean.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "latsim/capture/replay.hpp"

using namespace latsim::capture;
using latsim::des::RandomStream;
using latsim::des::Time;

namespace {

std::shared_ptr<const std::vector<Time>> values(std::vector<double> ms) {
  auto v = std::make_shared<std::vector<Time>>();
  for (double x : ms) v->push_back(Time::from_ms(x));
  return v;
}

std::vector<double> play(Replay& r, int n, RandomStream& s) {
  std::vector<double> out;
  for (int i = 0; i < n; ++i) out.push_back(r.next(s).to_ms());
  return out;
}

}  // namespace

TEST_CASE("in order: wrap goes back to the first value, stop says when all are played") {
  RandomStream s(1, "test");
  Replay wrap(values({1, 2, 3}), {});
  CHECK(play(wrap, 7, s) == std::vector<double>{1, 2, 3, 1, 2, 3, 1});
  CHECK(wrap.wraps() == 2);
  CHECK_FALSE(wrap.exhausted());
  Replay stop(values({1, 2, 3}), {.at_end = ReplayParams::AtEnd::stop});
  CHECK(play(stop, 2, s) == std::vector<double>{1, 2});
  CHECK_FALSE(stop.exhausted());
  CHECK(stop.next(s) == Time::ms(3));
  CHECK(stop.exhausted());
  CHECK(stop.played() == 3);
}

TEST_CASE("scale, offset and clipping; the mean is of the transformed values") {
  RandomStream s(1, "test");
  Replay r(values({1, 2, 10}), {.scale = 2.0, .offset_ms = 0.5, .max_ms = 5.0});
  // 1 × 2 + 0.5 = 2.5; 2 × 2 + 0.5 = 4.5; 10 × 2 + 0.5 = 20.5, clipped to 5.
  CHECK(play(r, 3, s) == std::vector<double>{2.5, 4.5, 5.0});
  CHECK(r.clipped_values() == 1);
  CHECK(r.mean() == Time::from_ms(4.0));  // (2.5 + 4.5 + 5) / 3
  CHECK_THROWS_AS(Replay(values({1, 2}), {.offset_ms = -1.5}), std::invalid_argument);
  CHECK_THROWS_AS(Replay(values({1, 2}), {.order = ReplayParams::Order::bootstrap, .block_length = 3}),
                  std::invalid_argument);
}

TEST_CASE("bootstrap: blocks of consecutive values, and streams of other replications differ") {
  std::vector<double> ms;
  for (int i = 0; i < 50; ++i) ms.push_back(i);
  const ReplayParams p{.order = ReplayParams::Order::bootstrap, .block_length = 5};
  RandomStream a(7, "capture", 0), b(7, "capture", 1);
  Replay ra(values(ms), p), rb(values(ms), p);
  const std::vector<double> xa = play(ra, 100, a), xb = play(rb, 100, b);
  CHECK(xa != xb);
  // Within each block of 5 the values follow each other, wrapping from 49 to 0.
  for (size_t i = 0; i < xa.size(); ++i)
    if (i % 5 != 0) CHECK(std::lround(xa[i]) == (std::lround(xa[i - 1]) + 1) % 50);
}

TEST_CASE("bootstrap: the pooled mean of many replications is the capture's mean") {
  // A column with a trend and a spike, so that blocks differ a lot.
  std::vector<double> ms;
  for (int i = 0; i < 40; ++i) ms.push_back(10.0 + 0.25 * i + (i == 17 ? 300.0 : 0.0) + (i % 3 == 0 ? 2.0 : 0.0));
  const int n = static_cast<int>(ms.size()), block = 8, blocks = 25, replications = 40;
  double mu = 0.0;
  for (double x : ms) mu += x / n;
  // Each block starts at a uniform index s, so its mean m_s (the circular
  // mean of 8 values from s) has expectation mu exactly, and variance
  // var_b = (1/n) sum_s (m_s - mu)^2. The pooled mean of R × K independent
  // blocks has standard error sqrt(var_b / (R K)); allow 4 of them (a false
  // failure has probability below 1e-4 by the normal approximation).
  double var_b = 0.0;
  for (int s = 0; s < n; ++s) {
    double m = 0.0;
    for (int k = 0; k < block; ++k) m += ms[static_cast<size_t>((s + k) % n)] / block;
    var_b += (m - mu) * (m - mu) / n;
  }
  const double tolerance = 4.0 * std::sqrt(var_b / (replications * blocks));
  double pooled = 0.0;
  std::vector<double> firsts;
  for (int r = 0; r < replications; ++r) {
    RandomStream stream(2026, "capture", static_cast<uint64_t>(r));
    Replay replay(values(ms), {.order = ReplayParams::Order::bootstrap, .block_length = block});
    for (int i = 0; i < block * blocks; ++i) pooled += replay.next(stream).to_ms();
    firsts.push_back(replay.next(stream).to_ms());
  }
  pooled /= static_cast<double>(replications) * block * blocks;
  CHECK(std::fabs(pooled - mu) <= tolerance);
  CHECK(tolerance < 3.0);  // the test says something: the spike alone moves a block mean by 37.5 ms
  CHECK(std::count(firsts.begin(), firsts.end(), firsts.front()) < replications);
}
