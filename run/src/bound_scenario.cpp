#include "latsim/run/bound_scenario.hpp"

#include <atomic>

#include "built_from.hpp"
#include "latsim/run/builtin_pipelines.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/schema.hpp"
#include "latsim/scenario/section.hpp"

namespace latsim::run {

using pipelines::PipelineFactory;
using pipelines::PipelineRegistry;

namespace {

// Scenarios bound by this process (binds_made()).
std::atomic<uint64_t> binds_made_{0};

/// Declares (reading mode: reads) the whole scenario: the shared sections,
/// then /pipeline through the declaration of the pipeline its "type" names.
PipelineFactory bind_scenario(scenario::Section& root, sections::SharedParams& shared, const PipelineRegistry& registry) {
  sections::bind(root, shared);
  PipelineFactory factory;
  std::vector<scenario::ModeDecl> modes;
  for (const auto& named : registry.entries()) {
    // A reference, not a structured binding: clang before 16 cannot capture bindings in a lambda.
    const auto& entry = named.second;
    modes.push_back(
        {named.first, entry.doc, [&factory, &shared, &entry](scenario::Section& p) { factory = entry.bind(p, shared); }});
  }
  int unused = 0;
  root.object("pipeline", unused,
              [&modes](scenario::Section& p, int&) {
                p.doc("The display strategy: which pose each image is computed from, when it is ready, and when it "
                      "goes into a front buffer. `type` selects the pipeline; each reads its own keys.");
                p.modes("type", "", modes, {.doc = "which pipeline"});
              },
              {.required = true, .doc = "the display strategy"});
  return factory;
}

}  // namespace

scenario::ObjectSchema schema_of(const PipelineRegistry& registry) {
  scenario::ObjectSchema root;
  scenario::Section s(root);
  sections::SharedParams shared;
  (void)bind_scenario(s, shared, registry);
  return root;
}

BoundScenario::BoundScenario(std::shared_ptr<const scenario::ScenarioDocument> doc, const PipelineRegistry* pipelines)
    : doc_(std::move(doc)) {
  const PipelineRegistry builtin = pipelines ? PipelineRegistry{} : builtin_pipelines();
  const PipelineRegistry& registry = pipelines ? *pipelines : builtin;
  built_from("", "scenario", [&] {
    scenario::Section root(doc_->root());
    factory_ = bind_scenario(root, shared_, registry);
    if (pipelines) {
      const scenario::ObjectSchema schema = schema_of(registry);
      doc_->check_unknown_keys(&schema, &input_warnings_);
    } else {
      doc_->check_unknown_keys(&scenario_schema(), &input_warnings_);
    }
  });
  binds_made_.fetch_add(1, std::memory_order_relaxed);
}

std::shared_ptr<const BoundScenario> BoundScenario::of(const scenario::ScenarioDocument& doc,
                                                       const PipelineRegistry* pipelines) {
  // An empty owner: the document is the caller's.
  return std::make_shared<const BoundScenario>(std::shared_ptr<const scenario::ScenarioDocument>(
                                                   std::shared_ptr<const scenario::ScenarioDocument>(), &doc),
                                               pipelines);
}

uint64_t binds_made() { return binds_made_.load(std::memory_order_relaxed); }

}  // namespace latsim::run
