// Builds a run from its scenario: binds every key (the shared sections, then
// /pipeline through the registered pipeline's declaration), resolves the
// clocks, builds the models the scenario asks for and the recorders, and lets
// the pipeline schedule its first events.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "latsim/des/run_clocks.hpp"
#include "latsim/des/simulator.hpp"
#include "latsim/display/display.hpp"
#include "latsim/sections/shared.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/results/frame_capture.hpp"
#include "latsim/results/frame_recorder.hpp"
#include "latsim/results/image_book.hpp"
#include "latsim/results/run_recording.hpp"
#include "latsim/results/run_files.hpp"
#include "latsim/results/smear_recorder.hpp"
#include "latsim/results/timeline.hpp"
#include "latsim/run/bound_scenario.hpp"
#include "latsim/run/event_budget.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/run/tracker_host.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/scenario/schema.hpp"
#include "latsim/tracker/motion_source.hpp"
#include "latsim/tracker/tracker.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::run {

/// Everything one run builds from its scenario.
struct Run {
  des::Simulator sim;
  /// The scenario as bound: its parameters, shared with every run built from it.
  std::shared_ptr<const BoundScenario> bound;
  std::unique_ptr<tracker::MotionSource> motion;
  std::unique_ptr<tracker::MotionSource> controller_motion;  ///< /controller's (null without one)
  std::unique_ptr<tracker::Tracker> tracker;
  std::unique_ptr<tracker::Transport> transport;
  std::unique_ptr<TrackerHost> host;
  std::unique_ptr<display::Display> display;
  results::ImageBook images;
  std::unique_ptr<results::RunRecording> recording;  ///< every recorder of the run and its figure book
  results::FrameRecorder app_frames;
  std::unique_ptr<results::FrameCapture> frames;  // only when the scenario asks for frames
  std::unique_ptr<results::SmearRecorder> smear;  // only on a display with persistence
  results::RunFiles files;
  std::unique_ptr<des::RunClocks> clocks;
  results::Timeline timeline;
  std::unique_ptr<pipelines::Pipeline> pipeline;
  std::unique_ptr<pipelines::RunContext> ctx;
  uint64_t seed = 1;
  /// The span simulated: the scenario's duration_s, until the run ends early
  /// (then where it ended); the pipeline reads this one value (RunContext::duration).
  des::Time duration;
  EventEstimate estimate;  ///< the events the run is expected to execute

  const sections::SharedParams& shared() const { return bound->shared(); }
};

/// Reads every key first, so that bad and unknown keys are reported before
/// anything is built; estimates the run's events and refuses it past
/// options.max_events; then builds every model and lets the pipeline
/// schedule its first events. Throws scenario::ScenarioError naming the pointer of
/// whatever could not be built.
void build(Run& run, const scenario::ScenarioDocument& doc, const RunOptions& options);
/// The same from a scenario already bound (a sweep point's replications
/// share one): the keys are not read again; the clocks, the models and the
/// pipeline are the run's own.
void build(Run& run, std::shared_ptr<const BoundScenario> bound, const RunOptions& options);

/// The scenario as built run `run` takes it: its document resolved, with the
/// phase of every clock the run decided (drawn or fixed), read from its clocks.
nlohmann::json resolved_scenario(const Run& run);

/// The registration probes of a built run: the scenario's, or a ring around the start pose.
results::ProbeSet probes_of(const Run& run);

}  // namespace latsim::run
