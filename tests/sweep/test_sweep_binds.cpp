// A sweep reads a point's scenario once per thread, not once per replication:
// its replications build their runs from one binding, and those runs are
// the runs a scenario bound on its own gives.
#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <numeric>
#include <string>
#include <vector>

#include "latsim/run/bound_scenario.hpp"
#include "latsim/run/prepared_run.hpp"
#include "latsim/sweep/common.hpp"
#include "latsim/sweep/runner.hpp"
#include "scratch_dir.hpp"

using namespace latsim;

namespace {

// Three points (60, 72 and 90 Hz) of 4 replications each, 50 ms runs of the
// polled serial HMD, whose clock phases are drawn per replication.
sweep::SweepPlan three_points(const std::filesystem::path& dir) {
  const std::string text = R"({
    "base": ")" LATSIM_SOURCE_DIR R"(/scenarios/hmd_60hz_serial_poll.json",
    "overrides": {"/duration_s": 0.05},
    "axes": [{"pointer": "/display/refresh_hz", "values": [60, 72, 90]}],
    "replications": 4,
    "seed": 3
  })";
  return sweep::read_plan((dir / "three_points.json").string(), text);
}

}  // namespace

TEST_CASE("a sweep binds each point once per thread and builds each run", "[sweep][binds]") {
  const std::filesystem::path dir = test::scratch_dir("latsim_sweep_binds");
  const sweep::SweepPlan plan = three_points(dir);
  REQUIRE(plan.runs().size() == 12);
  sweep::SweepRequest request;
  request.out_dir = (dir / "out").string();
  request.jobs = 1;
  std::vector<size_t> all(plan.runs().size());
  std::iota(all.begin(), all.end(), size_t{0});
  const uint64_t binds_before = run::binds_made(), builds_before = run::builds_made();
  const sweep::SweepOutcome outcome = sweep::run_sweep(plan, request, all, false, nullptr);
  REQUIRE_FALSE(outcome.problem);
  CHECK(outcome.tally.ran == 12);
  // Checking the points binds and builds each once (one run stands for its
  // replications: 3); on one thread a point's 4 replications follow one
  // another (replications are the plan's innermost loop, and the three
  // points cost the same, so the longest-first order keeps plan order): one
  // more binding a point (3), and every run its own models (12). Binding per
  // replication would make 3 + 12.
  CHECK(run::binds_made() - binds_before == 3 + 3);
  CHECK(run::builds_made() - builds_before == 3 + 12);
}

TEST_CASE("runs built from one binding are the runs of their own bindings", "[run][binds]") {
  // Drawn phases (none given) and a seed per run: everything a run decides
  // for itself, in runs that share a binding.
  const auto doc = scenario::ScenarioDocument::load(LATSIM_SOURCE_DIR "/scenarios/hmd_60hz_serial_poll.json",
                                                    {"/duration_s=0.2"});
  const auto shared = run::BoundScenario::of(doc, nullptr);
  for (uint64_t replication : {2u, 0u, 1u, 2u}) {
    INFO("replication " << replication);
    run::RunOptions options;
    options.replication = replication;
    options.seed = 11 + replication;
    const nlohmann::json from_shared = run::PreparedRun(shared, options).run();
    const auto own_doc = scenario::ScenarioDocument::load(LATSIM_SOURCE_DIR "/scenarios/hmd_60hz_serial_poll.json",
                                                          {"/duration_s=0.2"});
    const nlohmann::json from_own = run::PreparedRun(own_doc, options).run();
    CHECK(from_shared.at("fingerprint") == from_own.at("fingerprint"));
    CHECK(from_shared.at("events") == from_own.at("events"));
    CHECK(from_shared.at("figures") == from_own.at("figures"));
    CHECK(from_shared.at("scenario") == from_own.at("scenario"));
    CHECK(from_shared.at("warnings") == from_own.at("warnings"));
  }
}
