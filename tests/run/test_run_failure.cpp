// A model that fails in the middle of a run: the run names the model and the
// simulated time of the failing event, and leaves nothing on disk.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <stdexcept>

#include "latsim/pipelines/pipeline.hpp"
#include "latsim/run/builtin_pipelines.hpp"
#include "run_helpers.hpp"

using namespace latsim;
using Json = nlohmann::json;

namespace {

// A pipeline whose stage gives up at a set time: "faulty.stage" events every
// 10 ms from t = 0, the one at fail_at throws.
class FaultyPipeline : public pipelines::Pipeline {
 public:
  struct Params {
    des::Time fail_at;
  };
  explicit FaultyPipeline(Params p) : p_(p) {}
  void start(pipelines::RunContext& ctx) override {
    sim_ = &ctx.sim;
    kind_ = ctx.sim.kind("faulty.stage");
    schedule(des::Time::zero());
  }
  int64_t stages = 0;

 private:
  void schedule(des::Time t) {
    sim_->at(t, kind_, [this, t] {
      if (t == p_.fail_at) throw std::runtime_error("the stage gave up");
      ++stages;
      schedule(t + des::Time::from_seconds(0.01));
    });
  }
  Params p_;
  des::Simulator* sim_ = nullptr;
  des::KindId kind_ = 0;
};

void bind(scenario::Section& s, FaultyPipeline::Params& p, const sections::SharedParams&) {
  s.duration("fail_at_ms", p.fail_at, {.unit = "ms", .doc = "when the stage throws"});
}

pipelines::PipelineRegistry with_faulty() {
  pipelines::PipelineRegistry r = run::builtin_pipelines();
  r.add(pipelines::pipeline_entry<FaultyPipeline>("faulty", "a stage that throws at fail_at_ms"));
  return r;
}

}  // namespace

TEST_CASE("a model failing mid-run is named with the simulated time, and the run leaves no files", "[results]") {
  const auto parent = std::filesystem::temp_directory_path() / ("latsim_failure." + std::to_string(::getpid()));
  std::filesystem::remove_all(parent);
  std::filesystem::create_directories(parent);
  Json s = testing::base_scenario();
  s["pipeline"] = {{"type", "faulty"}, {"fail_at_ms", 250}};
  const pipelines::PipelineRegistry registry = with_faulty();
  run::RunOptions opt;
  opt.out_dir = parent / "run";
  opt.pipelines = &registry;
  const auto doc = scenario::ScenarioDocument::from_json(s, LATSIM_SOURCE_DIR "/scenarios");
  try {
    run::run_scenario(doc, opt);
    FAIL("the run did not fail");
  } catch (const run::RunFailure& e) {
    // The 26th stage event, at 25 × 10 ms: the kind's model and that time, exactly.
    CHECK(e.model() == "faulty");
    CHECK(e.at() == des::Time::from_seconds(0.25));
    CHECK(std::string(e.what()).find("the stage gave up") != std::string::npos);
  }
  // Neither the run directory nor its staging directory (nor anything else).
  CHECK(std::filesystem::is_empty(parent));
  std::filesystem::remove_all(parent);

  // The same pipeline failing after the run's end runs to completion.
  s["pipeline"]["fail_at_ms"] = 5000;
  const auto ok = run::run_scenario(scenario::ScenarioDocument::from_json(s, LATSIM_SOURCE_DIR "/scenarios"),
                                          run::RunOptions{.pipelines = &registry});
  CHECK(ok.at("events_per_model").contains("faulty"));
}
