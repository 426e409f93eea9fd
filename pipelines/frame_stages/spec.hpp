// What a staged frame pipeline is made of: processors, stages, buffers and
// the time warp, as plain values (the scenario binding fills them in).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "frame_stages/cost_shape.hpp"
#include "frame_stages/pacing.hpp"
#include "latsim/des/time.hpp"
#include "latsim/renderer/render_cost.hpp"

namespace latsim::pipelines::frame_stages {

/// A CPU thread, a GPU, a warp unit: it runs one stage at a time.
struct ProcessorSpec {
  std::string name;
  /// Work longer than this runs in slices; between slices a stage of another
  /// job waiting for the processor (the compositor) goes first: preemption.
  /// Zero: every stage runs to completion.
  des::Time preemption_slice;
  std::string pointer;  ///< where the scenario declares it (/pipeline/processors/i)
};

/// When a stage may begin, besides its processor being free and the same
/// stage of the previous job having begun.
enum class StartRule {
  after,    ///< when the previous stage of the job has ended
  stream,   ///< when the previous stage has run for `lag` (the GPU executing commands as
            ///< they are issued); it ends no earlier than that stage
  retrace,  ///< at the first retrace once the previous stage has ended (a vsync-paced thread)
  late,     ///< as late as the measured span up to the end of stage `until` still meets a deadline
  /// when the next job's first stage begins (and the previous stage has
  /// ended): an engine's render thread, handed its frame by the game thread
  /// starting the next one, so that game thread, render thread and GPU work
  /// on three frames at once
  next_frame,
};

/// One timed step of a job.
struct StageSpec {
  std::string name;
  std::vector<int> processors;  ///< indices into the processor list; several: used in turn (alternate frame rendering)
  renderer::RenderCost cost;              ///< how long it takes
  StartRule start = StartRule::after;
  des::Time lag;                ///< stream: how long the previous stage runs before this one starts
  des::Time offset;             ///< retrace: how long after the retrace it starts (render start offset)
  int until = -1;               ///< late: the stage whose end must meet the deadline (-1: this one)
  bool samples_pose = false;    ///< reads the head pose when it begins

  std::string pointer;          ///< where the scenario declares it (/pipeline/stages/i)
  CostShape shape;              ///< steps and spikes over the run (none: the cost model alone)
};

/// How late scheduling estimates a span: the longest of its nominal length
/// and the last `window` measured lengths, plus a safety margin.
struct LateParams {
  int window = 8;
  des::Time margin;
};

/// A compositor that re-projects the newest application image just before
/// it is scanned out.
struct WarpSpec {
  enum class Mode {
    rotation,    ///< orientation only: the position stays the rendered one
    positional,  ///< orientation and position, with the image's depth
    render,      ///< each strip rendered anew from the newest pose (beam racing)
  };
  Mode mode = Mode::rotation;
  std::vector<StageSpec> stages;
  int strips = 1;            ///< above 1: warp strip by strip just ahead of the beam, into the front buffer
  bool asynchronous = true;  ///< warp the last image again when no new one is ready
  bool half_rate = false;    ///< the application starts frames at every other refresh only
  /// false: a new frame is shown as rendered (it was predicted to its own
  /// photon time), and only a frame shown again is re-projected (SteamVR)
  bool reproject_new_frames = true;
  int eye_buffers = 2;       ///< application images the compositor can read from
};

/// The whole pipeline.
struct FrameStagesSpec {
  bool vsync = true;
  int max_frames_in_flight = 2;  ///< frame j starts only once frame j - N has completed its image
  int swap_chain_images = 2;     ///< without a warp: images drawn, queued and shown
  LateParams late;
  std::vector<ProcessorSpec> processors;
  std::vector<StageSpec> stages;
  std::optional<WarpSpec> warp;
  PacingSpec pacing;  ///< when the application's frames and the compositor's warps wake
};

}  // namespace latsim::pipelines::frame_stages
