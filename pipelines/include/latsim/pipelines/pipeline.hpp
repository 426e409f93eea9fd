// The pipeline interface: how a display strategy plugs into a latsim run.
//
// A run reads the scenario's shared sections into typed parameters, builds
// the shared models (head motion, tracker, transport, host mailbox, display,
// recorder) into a RunContext, reads /pipeline through the registered
// pipeline's own parameter declaration, calls start() to let it schedule its
// events, runs the simulator, then calls finish() to let it report figures.
// Pipelines present images to the display; the display and the recorder turn
// what is lit into latency and registration figures.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "latsim/sections/shared.hpp"
#include "latsim/pipelines/event_rate.hpp"
#include "latsim/pipelines/run_context.hpp"
#include "latsim/scenario/section.hpp"

namespace latsim::pipelines {

/// A display strategy: schedules its events in start(), reports in finish().
class Pipeline {
 public:
  virtual ~Pipeline() = default;
  /// Schedules the pipeline's first events (its parameters came with its construction).
  virtual void start(RunContext& ctx) = 0;
  /// Reports pipeline-specific figures to ctx.recorder (e.g. missed fields).
  virtual void finish(RunContext& /*ctx*/) {}
  /// Events per simulated second of the pipeline's own processes, each with
  /// the key that drives it (EventRate), known before start(); none
  /// declared: only the shared models' rates count against the event budget.
  virtual std::vector<EventRate> event_rates(const sections::SharedParams& /*shared*/) const { return {}; }
};

/// Builds a pipeline from parameters already read.
using PipelineFactory = std::function<std::unique_ptr<Pipeline>()>;

/// One registered pipeline: its name, what it is, and the function that
/// declares (and reads) its /pipeline keys and returns its factory.
struct PipelineEntry {
  std::string name;
  std::string doc;
  std::function<PipelineFactory(scenario::Section&, const sections::SharedParams&)> bind;
};

/// The entry of a pipeline class P with a nested `Params` struct, a function
/// `bind(scenario::Section&, P::Params&, const sections::SharedParams&)` found by
/// argument-dependent lookup, and a constructor from its Params.
template <class P>
PipelineEntry pipeline_entry(std::string name, std::string doc) {
  return PipelineEntry{std::move(name), std::move(doc),
                       [](scenario::Section& s, const sections::SharedParams& shared) -> PipelineFactory {
                         typename P::Params p{};
                         bind(s, p, shared);
                         return [p] { return std::make_unique<P>(p); };
                       }};
}

/// Pipelines by name, as the scenario's /pipeline/type selects them (the
/// builtin ones: run/'s builtin_pipelines()).
class PipelineRegistry {
 public:
  void add(PipelineEntry entry);
  const PipelineEntry* find(const std::string& name) const;
  std::vector<std::string> names() const;
  const std::map<std::string, PipelineEntry>& entries() const { return entries_; }

 private:
  std::map<std::string, PipelineEntry> entries_;
};

}  // namespace latsim::pipelines
