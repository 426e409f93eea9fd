// A scenario read once: every key bound, unknown keys checked and the
// pipeline's factory made. Runs that differ only in seed and replication (a
// sweep point's replications) build from one BoundScenario instead of
// reading the scenario again each.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "latsim/pipelines/pipeline.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/sections/shared.hpp"

namespace latsim::run {

/// The scenario's parameters as bound, ready to build any number of runs.
/// Binding reads every key (the shared sections, then /pipeline through the
/// declaration of the pipeline its "type" names) and refuses unknown keys;
/// nothing in it depends on a run's seed or replication (a clock's drawn
/// phase lives in the run's clocks, never here). Throws
/// scenario::ScenarioError naming the pointer of a key it cannot read.
/// Not copyable: a pipeline's factory may refer to the shared parameters.
class BoundScenario {
 public:
  /// Binds `doc` through `pipelines` (null: builtin_pipelines()). The
  /// document is kept (resolved() and the run's summary read it).
  BoundScenario(std::shared_ptr<const scenario::ScenarioDocument> doc, const pipelines::PipelineRegistry* pipelines);
  BoundScenario(const BoundScenario&) = delete;
  BoundScenario& operator=(const BoundScenario&) = delete;

  /// A bound scenario that refers to `doc` without owning it: `doc` must
  /// outlive it (a command's one run, its validation).
  static std::shared_ptr<const BoundScenario> of(const scenario::ScenarioDocument& doc,
                                                 const pipelines::PipelineRegistry* pipelines);

  const scenario::ScenarioDocument& doc() const { return *doc_; }
  const sections::SharedParams& shared() const { return shared_; }
  /// Keys read in another mode of their object (legal, but unused).
  const std::vector<std::string>& input_warnings() const { return input_warnings_; }
  /// A new pipeline of the bound parameters (one per run).
  std::unique_ptr<pipelines::Pipeline> make_pipeline() const { return factory_(); }

 private:
  std::shared_ptr<const scenario::ScenarioDocument> doc_;
  sections::SharedParams shared_;
  pipelines::PipelineFactory factory_;
  std::vector<std::string> input_warnings_;
};

/// The declaration of every key of a scenario whose pipelines are `registry`'s.
scenario::ObjectSchema schema_of(const pipelines::PipelineRegistry& registry);

/// How many scenarios this process has bound (each BoundScenario made).
uint64_t binds_made();

}  // namespace latsim::run
