// Tests for --keep: the four forms, which runs each keeps traces of (worked
// out by hand for a plan of 3 points x 2 replications), and the errors.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "latsim/sweep/keep.hpp"

using latsim::sweep::KeepPolicy;

namespace {

// Plan positions 0..5 of 3 points x 2 replications: position p is replication p % 2.
std::vector<size_t> kept_of(const KeepPolicy& keep) {
  std::vector<size_t> kept;
  for (size_t p = 0; p < 6; ++p)
    if (keep.keeps_traces(p, p % 2)) kept.push_back(p);
  return kept;
}

std::string error_of(const std::string& text) {
  try {
    (void)KeepPolicy::parse(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  FAIL("accepted --keep " << text);
  return {};
}

}  // namespace

TEST_CASE("keep: figures keeps no traces, all every run's, first replication 0's", "[sweep][keep]") {
  CHECK(kept_of(KeepPolicy::parse("figures")).empty());
  CHECK(kept_of(KeepPolicy{}).empty());
  CHECK(kept_of(KeepPolicy::parse("all")) == std::vector<size_t>{0, 1, 2, 3, 4, 5});
  CHECK(kept_of(KeepPolicy::parse("first")) == std::vector<size_t>{0, 2, 4});
}

TEST_CASE("keep: runs=I,J keeps exactly the listed plan positions", "[sweep][keep]") {
  const KeepPolicy keep = KeepPolicy::parse("runs=5,1,1");
  CHECK(keep.kind == KeepPolicy::Kind::runs);
  CHECK(kept_of(keep) == std::vector<size_t>{1, 5});
  CHECK(keep.text() == "runs=1,5");
  CHECK(KeepPolicy::parse(keep.text()).run_indices == keep.run_indices);
  CHECK_NOTHROW(keep.check_runs(6));
  CHECK_THROWS_WITH(keep.check_runs(5), Catch::Contains("run 5 is not in the plan, whose runs are 0 to 4"));
  CHECK_NOTHROW(KeepPolicy::parse("all").check_runs(1));
}

TEST_CASE("keep: anything else is an error that says what is expected", "[sweep][keep]") {
  for (const char* bad : {"", "First", "everything", "runs", "runs=", "runs=1,", "runs=,1", "runs=1;2", "runs=-1",
                          "runs=0x3", "runs= 1", "runs=99999999999999999999999"}) {
    INFO(bad);
    const std::string error = error_of(bad);
    CHECK_THAT(error, Catch::Contains("expected figures, first, all or runs=I,J"));
  }
  CHECK_THAT(error_of("runs=1,x"), Catch::Contains("\"x\" is not a run position"));
}
