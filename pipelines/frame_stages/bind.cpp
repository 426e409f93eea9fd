// /pipeline of frame_stages as the scenario writes it (processors and stages
// by name), every key declared once, resolved into a FrameStagesSpec.
#include <map>
#include <string>
#include <vector>

#include "frame_stages/frame_stages_pipeline.hpp"
#include "frame_stages/pacing_bind.hpp"
#include "latsim/des/time.hpp"
#include "latsim/sections/render_cost.hpp"
#include "latsim/sections/shared.hpp"
#include "latsim/pipelines/pipeline.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/scenario/section.hpp"

namespace latsim::pipelines::frame_stages {

namespace {

using scenario::Section;

/// How a stage's start is written; `automatic` resolves by position.
enum class StartKey { automatic, after, stream, retrace, late, next_frame };

struct ProcessorKeys {
  std::string name;
  int count = 1;
  des::Time preemption_slice;
};

struct StageKeys {
  std::string name;
  std::string on;
  StartKey start = StartKey::automatic;
  des::Time lag;
  des::Time offset;
  std::string until;
  bool samples_pose = false;
  renderer::RenderCost::Params cost;
  CostShape shape;
};

struct WarpKeys {
  WarpSpec::Mode mode = WarpSpec::Mode::rotation;
  int strips = 1;
  bool asynchronous = true;
  bool half_rate = false;
  bool reproject_new_frames = true;
  int eye_buffers = 2;
  std::vector<StageKeys> stages;
};

struct LateKeys {
  int window = 8;
  des::Time margin;
};

void bind(Section& s, ProcessorKeys& p) {
  s.text("name", p.name, {.required = true, .doc = "how stages name it"});
  s.integer("count", p.count,
            {.min = 1.0, .max = 16.0, .doc = "identical units (e.g. 2 GPUs), used in turn frame by frame"});
  s.duration("preemption_slice_ms", p.preemption_slice,
             {.unit = "ms", .doc = "0: a stage runs to completion; else it yields between slices of this length to a "
                                   "waiting stage of the other flow (GPU preemption by the compositor)"});
}

void bind(Section& s, StageKeys& st) {
  s.text("name", st.name, {.required = true, .doc = "I, S, R, G, W, ... (the timeline's stage name)"});
  s.text("on", st.on, {.required = true, .doc = "the processor that runs it"});
  s.choice("start", st.start,
           {{"auto", StartKey::automatic},
            {"after", StartKey::after},
            {"stream", StartKey::stream},
            {"retrace", StartKey::retrace},
            {"late", StartKey::late},
            {"next_frame", StartKey::next_frame}},
           {.doc = "after: when the previous stage ends; stream: lag_ms after the previous stage starts (commands "
                   "executed as issued); retrace: at the first retrace after the previous stage ends; late: as late "
                   "as the measured span to the end of `until` still meets its deadline; next_frame: when the next "
                   "frame's first stage begins, once the previous stage has ended (an engine's render thread a "
                   "frame behind its game thread); auto: retrace for an application's first stage with vsync (else "
                   "after), late for a warp's first stage, else after"});
  s.duration("lag_ms", st.lag, {.unit = "ms", .doc = "stream: how long the previous stage runs first"});
  s.duration("offset_ms", st.offset,
             {.unit = "ms", .doc = "retrace: start this long after the retrace (the render start offset; 0: at it)"});
  s.text("until", st.until, {.doc = "late: the stage whose end must meet the deadline (default: this one)"});
  s.flag("samples_pose", st.samples_pose, {.doc = "reads the head pose when it begins (the last such stage's pose is drawn)"});
  s.object("cost", st.cost, [](Section& c, renderer::RenderCost::Params& v) { sections::bind(c, v); },
           {.doc = "how long it takes (the render-cost model)"});
  s.object("cost_shape", st.shape, [](Section& c, CostShape& v) { bind_cost_shape(c, v); },
           {.doc = "steps and spikes of its cost over the run (docs/pacing.md)"});
}

/// Processor units by index, and the units each processor name stands for.
struct Units {
  std::vector<ProcessorSpec> specs;
  std::map<std::string, std::vector<int>> by_name;
};

Units expand(const std::vector<ProcessorKeys>& processors, const std::string& list_pointer) {
  Units u;
  for (size_t i = 0; i < processors.size(); ++i) {
    const ProcessorKeys& p = processors[i];
    std::vector<int>& idx = u.by_name[p.name];
    for (int k = 0; k < p.count; ++k) {
      idx.push_back(static_cast<int>(u.specs.size()));
      u.specs.push_back(ProcessorSpec{p.count == 1 ? p.name : p.name + std::to_string(k), p.preemption_slice,
                                      list_pointer + "/" + std::to_string(i)});
    }
  }
  return u;
}

/// Checks one stage list and turns it into stage specs.
std::vector<StageSpec> resolve(Section& s, const std::string& key, const std::vector<StageKeys>& stages,
                               const Units& units, StartRule first_default, const sections::SharedParams& shared) {
  std::vector<StageSpec> out;
  const display::RasterParams& raster = shared.display.raster;
  const int eyes = shared.host.stereo ? 2 : 1;
  bool samples = false;
  for (size_t i = 0; i < stages.size(); ++i) {
    const StageKeys& k = stages[i];
    const std::string at = s.pointer() + "/" + key + "/" + std::to_string(i);
    auto it = units.by_name.find(k.on);
    s.check_pointer(at + "/on", it != units.by_name.end(), "no processor is named " + scenario::quote_value(k.on));
    StageSpec st;
    st.name = k.name;
    st.pointer = at;
    st.processors = it->second;
    try {
      st.cost = sections::render_cost_for_scene(k.cost, shared.scene ? &*shared.scene : nullptr, raster.width_px,
                                              raster.height_px, eyes);
    } catch (const des::TimeOverflow& e) {
      s.check_pointer(at + "/cost", false, e.what());
    }
    switch (k.start) {
      case StartKey::automatic: st.start = i == 0 ? first_default : StartRule::after; break;
      case StartKey::after: st.start = StartRule::after; break;
      case StartKey::stream: st.start = StartRule::stream; break;
      case StartKey::retrace: st.start = StartRule::retrace; break;
      case StartKey::late: st.start = StartRule::late; break;
      case StartKey::next_frame: st.start = StartRule::next_frame; break;
    }
    s.check_pointer(at + "/start", !(st.start == StartRule::stream && i == 0), "the first stage has nothing to stream from");
    s.check_pointer(at + "/start", !(st.start == StartRule::next_frame && i == 0),
                    "the first stage is what the next frame begins with; next_frame is for a later stage");
    s.check_pointer(at + "/start",
                    !(st.start == StartRule::stream && i > 0 && out[i - 1].processors == st.processors),
                    "a stage streams from a stage on another processor");
    st.lag = k.lag;
    s.check_pointer(at + "/offset_ms", k.offset == des::Time::zero() || st.start == StartRule::retrace,
                    "only a stage that starts at a retrace has a start offset");
    st.offset = k.offset;
    if (!k.until.empty()) {
      int u = -1;
      for (size_t j = i; j < stages.size(); ++j)
        if (stages[j].name == k.until) u = static_cast<int>(j);
      s.check_pointer(at + "/until", u >= 0, scenario::quote_value(k.until) + " is not this stage or a later one");
      s.check_pointer(at + "/until", st.start == StartRule::late, "only a late stage has a span to meet a deadline");
      st.until = u;
    }
    st.samples_pose = k.samples_pose;
    st.shape = k.shape;
    samples = samples || k.samples_pose;
    out.push_back(std::move(st));
  }
  // `key` may be a path ("timewarp/stages"): check by pointer so its slash is not escaped as part of one key.
  const std::string list = s.pointer() + "/" + key;
  s.check_pointer(list, !stages.empty(), "give at least one stage");
  s.check_pointer(list, samples, "no stage reads the head pose: mark the input stage with \"samples_pose\": true");
  return out;
}

void bind_warp(Section& s, WarpKeys& w) {
  s.choice("mode", w.mode,
           {{"rotation", WarpSpec::Mode::rotation},
            {"positional", WarpSpec::Mode::positional},
            {"render", WarpSpec::Mode::render}},
           {.doc = "rotation: orientation only (the position stays the rendered one); positional: orientation and "
                   "position, with the image's depth; render: each strip rendered anew (beam racing)"});
  s.integer("strips", w.strips,
            {.min = 1.0, .max = 16384.0,
             .doc = "1: the whole image before each retrace; more: strip by strip just ahead of the beam, into the "
                    "front buffer (line or pixel scanout)"});
  s.flag("asynchronous", w.asynchronous, {.doc = "warp the last image again when no new one is ready"});
  s.flag("half_rate", w.half_rate,
         {.doc = "the application starts frames at every other retrace; the compositor synthesises the others"});
  s.integer("eye_buffers", w.eye_buffers, {.min = 2.0, .max = 16.0, .doc = "application images the compositor reads from"});
  s.choice("reproject", w.reproject_new_frames, {{"every_refresh", true}, {"repeats", false}},
           {.doc = "every_refresh: every image is re-projected to the newest pose; repeats: a new frame is shown as "
                   "rendered (predicted to its photon time) and only a frame shown again is re-projected (SteamVR)"});
  s.objects("stages", w.stages, [](Section& e, StageKeys& v) { bind(e, v); },
            {.required = true, .doc = "the compositor's stages, per warp"});
}

}  // namespace

void bind(Section& s, FrameStagesPipeline::Params& p, const sections::SharedParams& shared) {
  FrameStagesSpec& spec = p.spec;
  s.flag("vsync", spec.vsync,
         {.doc = "frames are swapped in at a retrace (in order, each at least once); false: shown as they complete "
                 "(tearing)"});
  s.integer("max_frames_in_flight", spec.max_frames_in_flight,
            {.min = 1.0, .max = 16.0, .doc = "frame j starts once frame j - N has completed its image (1: no CPU/GPU overlap)"});
  s.integer("swap_chain_images", spec.swap_chain_images,
            {.min = 2.0, .max = 16.0, .doc = "without a time warp: images drawn, queued and shown"});
  LateKeys late;
  s.object("late", late,
           [](Section& l, LateKeys& v) {
             l.integer("window", v.window, {.min = 1.0, .max = 100000.0, .doc = "measured spans remembered"});
             l.duration("margin_ms", v.margin, {.unit = "ms", .doc = "added to the estimate"});
           },
           {.doc = "how late scheduling estimates a span: the longest of its nominal length and the last `window` "
                   "measured ones, plus `margin_ms`"});
  spec.late = LateParams{late.window, late.margin};
  std::vector<ProcessorKeys> processors;
  s.objects("processors", processors, [](Section& e, ProcessorKeys& v) { bind(e, v); },
            {.required = true, .doc = "CPU threads, GPUs, a warp unit: each runs one stage at a time"});
  std::vector<StageKeys> stages;
  s.objects("stages", stages, [](Section& e, StageKeys& v) { bind(e, v); },
            {.required = true, .doc = "one frame, in order"});
  std::optional<WarpKeys> warp;
  s.optional_object("timewarp", warp, [](Section& w, WarpKeys& v) { bind_warp(w, v); },
                    {.doc = "a compositor re-projecting the newest image just before it is scanned out"});
  PacingKeys pacing;
  s.object("pacing", pacing, [](Section& e, PacingKeys& v) { bind_pacing(e, v); },
           {.doc = "when the application's frames and the compositor's warps wake (docs/pacing.md)"});
  s.rule("processors", "processor names are unique");
  s.rule("stages",
         "each stage runs `on` a processor; a stream stage follows a stage on another processor; `until` names "
         "this stage or a later one of a late stage; some stage `samples_pose`");
  s.rule("timewarp", "`strips` above 1 need line or pixel scanout, at most one strip per line");
  if (s.describing()) return;
  for (size_t i = 0; i < processors.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      s.check_pointer(s.pointer() + "/processors/" + std::to_string(i) + "/name", processors[i].name != processors[j].name,
                      "two processors are named " + scenario::quote_value(processors[i].name));
  const Units units = expand(processors, s.pointer() + "/processors");
  spec.processors = units.specs;
  spec.stages = resolve(s, "stages", stages, units, spec.vsync ? StartRule::retrace : StartRule::after, shared);
  des::Time total;
  bool paced = false;
  for (const StageSpec& st : spec.stages) {
    total += st.cost.nominal_frame_time();
    paced = paced || st.start == StartRule::retrace || st.start == StartRule::late;
  }
  int handovers = 0;
  for (const StageSpec& st : spec.stages) handovers += st.start == StartRule::next_frame ? 1 : 0;
  s.check("max_frames_in_flight", spec.max_frames_in_flight > handovers,
          "each next_frame stage keeps one more frame in flight: max_frames_in_flight must exceed their number");
  s.check("vsync", paced || total > des::Time::zero(),
          "frames that take no time and wait for nothing would follow each other without end: give a stage a cost");
  resolve_pacing(s, pacing, spec.stages, warp.has_value());
  spec.pacing = pacing.spec;
  if (!warp) return;
  WarpSpec w;
  w.mode = warp->mode;
  w.strips = warp->strips;
  w.asynchronous = warp->asynchronous;
  w.half_rate = warp->half_rate;
  w.reproject_new_frames = warp->reproject_new_frames;
  w.eye_buffers = warp->eye_buffers;
  const std::string tw = s.pointer() + "/timewarp";
  const int lines = shared.display.raster.interlaced ? shared.display.raster.height_px / 2 : shared.display.raster.height_px;
  s.check_pointer(tw + "/strips", w.strips <= lines, "a field has at most one strip per line");
  s.check_pointer(tw + "/strips", w.strips == 1 || shared.display.fidelity != display::ScanoutFidelity::Field,
                  "strips are written into the front buffer as the beam goes: use \"scanout\": \"line\" or \"pixel\"");
  w.stages = resolve(s, "timewarp/stages", warp->stages, units, StartRule::late, shared);
  spec.warp = w;
}

}  // namespace latsim::pipelines::frame_stages

namespace latsim::pipelines {

PipelineEntry frame_stages_pipeline() {
  return pipeline_entry<frame_stages::FrameStagesPipeline>(
      "frame_stages",
      "Today's pipelines: a frame is a sequence of timed stages (input sampling, simulation, render submission, GPU "
      "drawing) on named processors (CPU threads, GPUs), with vsync or not, frames in flight, streaming, "
      "vsync-paced threads and late scheduling; an optional compositor re-projects the newest image before each "
      "retrace (asynchronous time warp, rotation only or with depth) or strip by strip just ahead of the beam "
      "(continuous time warp). See docs/modern.md.");
}

}  // namespace latsim::pipelines
