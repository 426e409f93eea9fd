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
#include "latsim/results/latency_recorder.hpp"
#include "latsim/results/run_files.hpp"
#include "latsim/results/smear_recorder.hpp"
#include "latsim/results/timeline.hpp"
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
  sections::SharedParams shared;
  std::vector<std::string> input_warnings;
  std::unique_ptr<tracker::MotionSource> motion;
  std::unique_ptr<tracker::MotionSource> controller_motion;  ///< /controller's (null without one)
  std::unique_ptr<tracker::Tracker> tracker;
  std::unique_ptr<tracker::Transport> transport;
  std::unique_ptr<TrackerHost> host;
  std::unique_ptr<display::Display> display;
  results::ImageBook images;
  std::unique_ptr<results::LatencyRecorder> recorder;
  results::FrameRecorder app_frames;
  std::unique_ptr<results::FrameCapture> frames;  // only when the scenario asks for frames
  std::unique_ptr<results::SmearRecorder> smear;  // only on a display with persistence
  results::RunFiles files;
  std::unique_ptr<des::RunClocks> clocks;
  results::Timeline timeline;
  std::unique_ptr<pipelines::Pipeline> pipeline;
  std::unique_ptr<pipelines::RunContext> ctx;
  uint64_t seed = 1;
  des::Time duration;
  EventEstimate estimate;  ///< the events the run is expected to execute
};

/// Reads every key first, so that bad and unknown keys are reported before
/// anything is built; estimates the run's events and refuses it past
/// options.max_events; then builds every model and lets the pipeline
/// schedule its first events. Throws scenario::ScenarioError naming the pointer of
/// whatever could not be built.
void build(Run& run, const scenario::ScenarioDocument& doc, const RunOptions& options);

/// The declaration of every key of a scenario whose pipelines are `registry`'s.
scenario::ObjectSchema schema_of(const pipelines::PipelineRegistry& registry);

/// The registration probes of a built run: the scenario's, or a ring around the start pose.
results::ProbeSet probes_of(const Run& run);

}  // namespace latsim::run
