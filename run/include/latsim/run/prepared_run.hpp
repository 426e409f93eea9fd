// One scenario parsed, bound and built once, then validated, estimated and
// run from that one build.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/run/bound_scenario.hpp"
#include "latsim/run/event_budget.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

namespace latsim::run {

struct Run;

/// A scenario built for a run: every key read, the clocks resolved, the
/// models, the recorders and the pipeline built and its first events
/// scheduled. What validation reports (the warnings about legal but doubtful
/// input, the event estimate refused past options.max_events) and the run
/// itself come from this one build; nothing touches the output directory
/// until run(). Throws scenario::ScenarioError naming the pointer of
/// whatever could not be built.
class PreparedRun {
 public:
  /// Binds `doc` (which must outlive this) and builds the run.
  PreparedRun(const scenario::ScenarioDocument& doc, RunOptions options);
  /// Builds the run from a scenario already bound (a sweep point's
  /// replications share one), reading no key again.
  PreparedRun(std::shared_ptr<const BoundScenario> bound, RunOptions options);
  ~PreparedRun();
  PreparedRun(const PreparedRun&) = delete;
  PreparedRun& operator=(const PreparedRun&) = delete;

  /// The scenario as this run takes it: every default applied and the
  /// phase of every clock, drawn or fixed (summary.json's "scenario" less
  /// the default probe ring).
  nlohmann::json resolved() const;
  /// Legal but doubtful input, as the run will report it.
  const std::vector<std::string>& warnings() const;
  /// The events the run is expected to execute (docs/event-budget.md): the
  /// one estimate of a run, for its budget and a sweep's order alike.
  const EventEstimate& estimate() const;
  /// Simulates and writes the results as run_scenario describes; once.
  nlohmann::json run();

 private:
  RunOptions options_;
  std::unique_ptr<Run> run_;
  bool ran_ = false;
};

/// How many runs this process has built (every PreparedRun, run_scenario,
/// validate_scenario and estimate_scenario_events builds one): a command
/// builds each scenario it runs once.
uint64_t builds_made();

}  // namespace latsim::run
