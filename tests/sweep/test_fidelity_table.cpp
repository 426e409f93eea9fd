// Tests for the fidelity table: --vary parsing, errors against the finest
// level (exactly zero there), and the CSV layout.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "latsim/sweep/fidelity_table.hpp"

using latsim::sweep::compute_errors;
using latsim::sweep::fidelity_csv;
using latsim::sweep::FidelityLevel;
using latsim::sweep::level_dir_name;
using latsim::sweep::parse_vary;

TEST_CASE("the vary option splits a pointer and its levels, coarsest first", "[fidelity]") {
  const auto axis = parse_vary("/display/scanout=field,line,pixel");
  CHECK(axis.pointer == "/display/scanout");
  REQUIRE(axis.values.size() == 3);
  CHECK(axis.values.back() == "pixel");
  CHECK_THROWS_AS(parse_vary("display/scanout=field,line"), std::invalid_argument);
  CHECK_THROWS_AS(parse_vary("/display/scanout"), std::invalid_argument);
  CHECK_THROWS_WITH(parse_vary("/display/scanout=field"), Catch::Contains("at least two"));
  CHECK_THROWS_WITH(parse_vary("/display/scanout=field,,pixel"), Catch::Contains("empty value"));
}

TEST_CASE("errors are against the last level and exactly zero there", "[fidelity]") {
  std::vector<FidelityLevel> levels(3);
  levels[0].metric = 42.1;
  levels[1].metric = 41.95;
  // A value with no short binary form: x - x must still be exactly 0.
  levels[2].metric = 42.0 + 1.0 / 3.0;
  compute_errors(levels);
  CHECK(levels[2].abs_error == 0.0);
  CHECK(levels[2].rel_error == 0.0);
  CHECK(levels[0].abs_error == Approx(std::fabs(42.1 - levels[2].metric)));
  CHECK(levels[1].rel_error == Approx(std::fabs(41.95 - levels[2].metric) / levels[2].metric));

  std::vector<FidelityLevel> zero_reference(2);
  zero_reference[0].metric = 1.0;
  compute_errors(zero_reference);
  CHECK(std::isinf(zero_reference[0].rel_error));
  CHECK(zero_reference[1].rel_error == 0.0);
}

TEST_CASE("fidelity.csv has one row per level with the knob and metric as headers", "[fidelity]") {
  const auto axis = parse_vary("/display/scanout=field,line");
  std::vector<FidelityLevel> levels(2);
  levels[0] = {"field", 2.5, 0.1, 1800, 8.5, 0, 0};
  levels[1] = {"line", 2.0, 0.2, 289800, 9.0, 0, 0};
  compute_errors(levels);
  CHECK(fidelity_csv(axis, "motion_to_photon_ms.p99", levels) ==
        "level,/display/scanout,motion_to_photon_ms.p99,abs_error,rel_error,wall_s,events,peak_rss_mb\n"
        "0,field,2.5,0.5,0.25,0.1,1800,8.5\n"
        "1,line,2,0,0,0.2,289800,9\n");
  CHECK(level_dir_name(2, "60000/1001") == "2_60000_1001");
}
