// The optimiser's search: golden-section on a known parabola and on a
// bounded monotone figure, the comparison of trials, bounds as written, and
// the bisection capacity shares.
#include <catch2/catch.hpp>

#include <cmath>

#include "latsim/sweep/optimise.hpp"

using namespace latsim::sweep;

TEST_CASE("golden-section finds the minimum of a parabola within the tolerance, in the predicted evaluations",
          "[optimise]") {
  int calls = 0;
  auto parabola = [&](double x) {
    ++calls;
    Trial t;
    t.x = x;
    t.objective = (x - 3.3) * (x - 3.3);
    return t;
  };
  const SearchResult r = golden_section(parabola, 0.0, 10.0, 1e-3);
  CHECK(std::abs(r.best.x - 3.3) <= 1e-3);
  // Each step keeps 1/phi = 0.618 of the interval and costs one evaluation:
  // 10 x 0.618^n <= 1e-3 takes n = ceil(ln(1e4) / ln(1.618)) = 20 steps,
  // after the 2 first probes; then the 2 ends.
  const int steps = static_cast<int>(std::ceil(std::log(1e4) / std::log((1 + std::sqrt(5.0)) / 2)));
  CHECK(steps == 20);
  CHECK(calls == 2 + steps + 2);
  CHECK(r.tried.size() == static_cast<size_t>(calls));
}

TEST_CASE("a bound is kept first: the best of a falling figure lies at the bound", "[optimise]") {
  // Minimise -x (prefer large x) with x <= 6.5: the merit (violation,
  // objective) falls to 6.5, then rises in its violation.
  auto bounded = [](double x) {
    Trial t;
    t.x = x;
    t.objective = -x;
    t.violation = std::max(0.0, x - 6.5);
    return t;
  };
  const SearchResult r = golden_section(bounded, 0.0, 10.0, 1e-4);
  CHECK(r.best.violation == 0.0);
  CHECK(r.best.x <= 6.5);
  CHECK(r.best.x >= 6.5 - 1e-4);
  // A monotone merit has its best at an end: the ends are tried too.
  auto falling = [](double x) {
    Trial t;
    t.x = x;
    t.objective = -x;
    return t;
  };
  CHECK(golden_section(falling, 0.0, 10.0, 0.1).best.x == 10.0);
}

TEST_CASE("trials compare by violation, then objective, then setting", "[optimise]") {
  Trial feasible{1.0, 5.0, 0.0, {}}, infeasible{2.0, -100.0, 0.1, {}}, tie{0.5, 5.0, 0.0, {}};
  CHECK(better(feasible, infeasible));
  CHECK_FALSE(better(infeasible, feasible));
  CHECK(better(tie, feasible));
}

TEST_CASE("bounds read as written", "[optimise]") {
  const auto a = parse_bound("frames_missed<=2");
  REQUIRE(a);
  CHECK(a->figure == "frames_missed");
  CHECK(a->at_most);
  CHECK(a->bound == 2.0);
  const auto b = parse_bound("application_frame_rate_hz>=89.5");
  REQUIRE(b);
  CHECK_FALSE(b->at_most);
  CHECK(b->bound == 89.5);
  CHECK_FALSE(parse_bound("frames_missed<2"));
  CHECK_FALSE(parse_bound("<=2"));
  CHECK_FALSE(parse_bound("x<=two"));
  CHECK_FALSE(parse_bound("x<=inf"));
}

TEST_CASE("bisection finds the largest fitting count", "[optimise]") {
  int calls = 0;
  auto fits = [&](int64_t n) {
    ++calls;
    return n <= 37;
  };
  CHECK(largest_fitting(fits, 0, 100) == 37);
  // Both ends, then ceil(log2(100)) = 7 halvings at most.
  CHECK(calls <= 2 + 7);
  CHECK(largest_fitting(fits, 0, 20) == 20);
  CHECK_FALSE(largest_fitting(fits, 40, 100));
}

TEST_CASE("a search's settings are rounded to what the key accepts, within the interval", "[optimise]") {
  // A frequency given as a number has at most 6 decimals (micro-hertz):
  // 1000.1234567891 is 1000.123457 (the seventh decimal, 7, rounds up).
  CHECK(setting_in_steps(1000.1234567891, 500.0, 2000.0, 6) == 1000.123457);
  CHECK(setting_in_steps(138.52908, 100.1, 200.7, 6) == 138.52908);
  // The nearest step, 60.000000, lies below the interval: the next one up.
  CHECK(setting_in_steps(60.0000004, 60.0000004, 61.0, 6) == 60.000001);
  // The nearest, 61.000000, above it: the next one down.
  CHECK(setting_in_steps(60.9999996, 60.0, 60.9999996, 6) == 60.999999);
  // No micro-hertz step between 60.0000001 and 60.0000004.
  CHECK_FALSE(setting_in_steps(60.0000002, 60.0000001, 60.0000004, 6).has_value());
  // An integer key: whole numbers (2.6 is 3); none between 2.2 and 2.8.
  CHECK(setting_in_steps(2.6, 1.0, 10.0, 0) == 3.0);
  CHECK_FALSE(setting_in_steps(2.5, 2.2, 2.8, 0).has_value());
  // Any other key: the setting as it is.
  CHECK(setting_in_steps(0.1 + 0.2, 0.0, 1.0, std::nullopt) == 0.1 + 0.2);
}

TEST_CASE("the steps come from the key's declaration: a rate 6 decimals, an integer 0, others none", "[optimise]") {
  latsim::scenario::KeySchema rate, integer, number;
  rate.type = "rate";
  integer.type = "integer";
  number.type = "number";
  CHECK(setting_decimals(&rate) == 6);
  CHECK(setting_decimals(&integer) == 0);
  CHECK_FALSE(setting_decimals(&number).has_value());
  CHECK_FALSE(setting_decimals(nullptr).has_value());
}
