// /pipeline of present_replay: the capture and process to replay, and the
// present path (the capture's own unless the scenario says otherwise).
#include "latsim/pipelines/pipeline.hpp"
#include "present_replay/present_replay_pipeline.hpp"

namespace latsim::pipelines::present_replay {

namespace {

using scenario::Section;

/// The keys as the scenario writes them.
struct CaptureKeys {
  std::filesystem::path file;
  std::string application;
  int64_t process_id = 0;
};

enum class ModeChoice { capture, hardware, composed };
enum class TearingChoice { capture, allowed, not_allowed };

void bind_capture(Section& c, CaptureKeys& k) {
  c.path("file", k.file, {.required = true, .doc = "a PresentMon capture (current, v1 or v2 columns), relative to the "
                                                  "file that names it"});
  c.text("application", k.application, {.doc = "keep the frames of this Application (any ASCII case); empty: any"});
  c.integer("process_id", k.process_id,
            {.min = 0.0, .doc = "keep the frames of this ProcessID; 0: any (the frames kept must be of one process)"});
}

// The capture's path, then what the scenario changes of it.
PresentPathSpec resolve_path(const capture::PresentMonProcess& pm, ModeChoice mode, int sync, TearingChoice tearing,
                             int latency) {
  capture::PresentMonProcess as = pm;
  for (capture::PresentMonFrame& f : as.frames) {
    if (mode == ModeChoice::hardware) f.mode = capture::PresentMode::hardware_independent_flip;
    if (mode == ModeChoice::composed) f.mode = capture::PresentMode::composed_flip;
    if (sync >= 0) f.sync_interval = sync;
    if (tearing != TearingChoice::capture) f.allows_tearing = tearing == TearingChoice::allowed;
  }
  return capture_path(as, latency);
}

}  // namespace

/// Reads /pipeline of present_replay (found by pipeline_entry through its Params).
void bind(Section& s, PresentReplayPipeline::Params& p, const sections::SharedParams&) {
  CaptureKeys keys;
  s.object("capture", keys, [](Section& c, CaptureKeys& k) { bind_capture(c, k); },
           {.required = true, .doc = "the capture and the process whose frames are replayed"});
  ModeChoice mode = ModeChoice::capture;
  s.choice("present_mode", mode,
           {{"capture", ModeChoice::capture}, {"hardware", ModeChoice::hardware}, {"composed", ModeChoice::composed}},
           {.doc = "capture: the PresentMode most of the process's frames had; hardware: flipped by the display "
                   "itself; composed: through the desktop compositor (a refresh later)"});
  int sync = -1;
  s.integer("sync_interval", sync,
            {.min = -1.0, .max = 4.0, .doc = "refreshes a frame stays on screen at least; 0: not waiting for a "
                                             "refresh; -1: the capture's (its own -1, not reported, taken as 1)"});
  TearingChoice tearing = TearingChoice::capture;
  s.choice("tearing", tearing,
           {{"capture", TearingChoice::capture}, {"allowed", TearingChoice::allowed}, {"not_allowed", TearingChoice::not_allowed}},
           {.doc = "with sync interval 0, whether a frame may replace another mid-scan (capture: its AllowsTearing)"});
  int latency = 3;
  s.integer("max_frame_latency", latency,
            {.min = 1.0, .max = 16.0, .doc = "frames presented and not yet taken by the display before a Present waits "
                                             "(DXGI's default maximum frame latency: 3)"});
  using AtEnd = capture::ReplayParams::AtEnd;
  s.choice("at_end", p.at_end, {{"wrap", AtEnd::wrap}, {"stop", AtEnd::stop}},
           {.doc = "after the last frame: wrap: the first again; stop: the run ends there (with a warning)"});
  if (s.describing()) return;
  p.pointer = s.pointer() + "/capture";
  s.guard("capture", [&] {
    capture::ProcessSelect select{keys.application, std::nullopt};
    if (keys.process_id != 0) select.process_id = keys.process_id;
    p.source = load_replay_source(keys.file, select);
  });
  p.path = resolve_path(p.source->process, mode, sync, tearing, latency);
  p.mode_text = mode == ModeChoice::capture ? capture::present_mode_text(p.source->process.mode())
                : mode == ModeChoice::hardware ? "Hardware: Independent Flip"
                                               : "Composed: Flip";
}

}  // namespace latsim::pipelines::present_replay

namespace latsim::pipelines {

PipelineEntry present_replay_pipeline() {
  using present_replay::PresentReplayPipeline;
  return pipeline_entry<PresentReplayPipeline>(
      "present_replay",
      "Replays one process of a PresentMon capture on the scenario's display: each frame's application time before "
      "its Present (CPU busy, waiting included, as PresentMon defines it), its time in Present (CPU wait, and longer "
      "while the present path is full) and its GPU work, shown through the present path the capture ran on (sync "
      "interval, present mode, tearing). See docs/measured.md.");
}

}  // namespace latsim::pipelines
