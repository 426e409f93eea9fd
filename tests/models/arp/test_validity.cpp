// Validity periods: the chord formula's accuracy and the zero-speed cases.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "latsim/arp/harmonic_memories.hpp"
#include "latsim/arp/validity.hpp"

using namespace latsim;

namespace {

// 2 d sin(theta/2) by the Taylor series of sin in long double, summed until
// the terms vanish: an independent, more precise reference.
long double chord_reference(long double d, long double theta) {
  const long double h = theta / 2.0L;
  long double term = h;
  long double sum = 0.0L;
  for (int n = 1; n < 60; n += 2) {
    sum += term;
    term *= -h * h / static_cast<long double>((n + 1) * (n + 2));
    if (std::fabs(term) < 1e-40L * std::fabs(sum)) break;
  }
  return 2.0L * d * sum;
}

}  // namespace

TEST_CASE("chord distance is accurate from 1e-12 rad and up to 1e6 m") {
  for (double theta : {1e-12, 3e-11, 1e-9, 1e-7, 1e-5, 1e-3, 0.0174533, 0.3, 1.0}) {
    for (double d : {1e-3, 0.5, 1.0, 20.0, 1e3, 1e6}) {
      const double x = arp::translational_validity_distance_m(d, theta);
      REQUIRE(std::isfinite(x));
      const long double ref = chord_reference(d, theta);
      const double rel = static_cast<double>(std::fabs((static_cast<long double>(x) - ref) / ref));
      INFO("theta " << theta << " d " << d << " x " << x);
      CHECK(rel < 4e-16);
    }
  }
}

TEST_CASE("the cosine form of the chord cancels, which is why it is not used") {
  const double theta = 1e-9;
  const double d = 10.0;
  const double naive = d * std::sqrt(2.0 * (1.0 - std::cos(theta)));
  const double ref = static_cast<double>(chord_reference(d, theta));
  CHECK(std::fabs(naive - ref) / ref > 1e-3);
  CHECK(arp::translational_validity_distance_m(d, theta) == Approx(ref).epsilon(1e-15));
}

TEST_CASE("chord distance at zero distance is zero and bad angles are refused") {
  CHECK(arp::translational_validity_distance_m(0.0, 1e-3) == 0.0);
  CHECK_THROWS(arp::translational_validity_distance_m(1.0, 0.0));
  CHECK_THROWS(arp::translational_validity_distance_m(1.0, std::nan("")));
  CHECK_THROWS(arp::translational_validity_distance_m(-1.0, 1e-3));
}

TEST_CASE("zero relative speed gives infinite validity without NaN") {
  renderer::Aabb box;
  box.extend(glm::dvec3(-1.0, 0.0, -5.0));
  box.extend(glm::dvec3(1.0, 2.0, -4.0));
  for (glm::dvec3 eye : {glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0, 1.0, -4.5)}) {  // outside, then inside
    const arp::ObjectView view = arp::view_of(box, eye, glm::dvec3(0.0), 0.0);
    const arp::ValidityPeriods p = arp::validity_periods(view, 1e-3);
    CHECK(std::isinf(p.translational_s));
    CHECK(std::isinf(p.size_s));
    CHECK(std::isinf(p.animation_s));
    CHECK(std::isinf(p.min_s()));
    CHECK(p.min_s() > 0.0);
  }
  // A point object seen from its own position: zero distance, zero radius.
  renderer::Aabb point;
  point.extend(glm::dvec3(0.0));
  const arp::ValidityPeriods p = arp::validity_periods(arp::view_of(point, glm::dvec3(0.0), glm::dvec3(0.0), 0.0), 1e-3);
  CHECK(std::isinf(p.min_s()));
  CHECK(std::isinf(arp::period_from_distance_s(0.0, 0.0)));
}

TEST_CASE("validity is the minimum of translation, size and animation") {
  renderer::Aabb box;
  box.extend(glm::dvec3(-0.5, -0.5, -10.5));
  box.extend(glm::dvec3(0.5, 0.5, -9.5));
  const double theta = 1e-3;
  // Walking sideways at 1 m/s: translation only (no radial component).
  arp::ValidityPeriods side =
      arp::validity_periods(arp::view_of(box, glm::dvec3(0.0), glm::dvec3(-1.0, 0.0, 0.0), 0.0), theta);
  CHECK(side.translational_s == Approx(2.0 * 9.5 * std::sin(theta / 2.0)));
  CHECK(std::isinf(side.size_s));
  // Walking straight at it: the size term now counts and is smaller.
  arp::ValidityPeriods ahead =
      arp::validity_periods(arp::view_of(box, glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0), 0.25), theta);
  CHECK(std::isfinite(ahead.size_s));
  CHECK(ahead.min_s() == Approx(std::min({ahead.translational_s, ahead.size_s, 0.25})));
  // The stable size formula equals cot(a) - cot(a + delta) where that is well conditioned.
  const double r = 0.8;
  const double d = 10.0;
  const double a = std::atan2(r, d);
  const double direct = r / std::tan(a) - r / std::tan(a + theta / 2.0);
  CHECK(arp::size_validity_distance_m(d, r, theta) == Approx(direct).epsilon(1e-9));
}

TEST_CASE("harmonic memories halve their rate and pick the slowest valid one") {
  arp::HarmonicMemories mem(des::RationalSeconds{1, 60}, 4);
  CHECK(mem.rate_hz(0) == Approx(60.0));
  CHECK(mem.rate_hz(1) == Approx(30.0));
  CHECK(mem.rate_hz(2) == Approx(15.0));
  CHECK(mem.rate_hz(3) == Approx(7.5));
  CHECK(mem.memory_for_validity(0.001) == 0);
  CHECK(mem.memory_for_validity(1.0 / 60.0) == 0);
  CHECK(mem.memory_for_validity(0.04) == 1);
  CHECK(mem.memory_for_validity(0.1) == 2);
  CHECK(mem.memory_for_validity(std::numeric_limits<double>::infinity()) == 3);
  CHECK(mem.has_slot(3, 16));
  CHECK_FALSE(mem.has_slot(3, 12));
  CHECK_THROWS(arp::HarmonicMemories(des::RationalSeconds{1, 60}, 0));
}
