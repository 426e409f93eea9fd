// Builds the shared models by hand around a frame_stages pipeline given as a
// spec, so that the engine is tested without a scenario file.
#pragma once

#include <memory>

#include "frame_stages/frame_stages_pipeline.hpp"
#include "latsim/des/simulator.hpp"
#include "latsim/display/display.hpp"
#include "latsim/pipelines/latency_recorder.hpp"
#include "latsim/pipelines/tracker_host.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::testing {

namespace fs = pipelines::frame_stages;

/// Fixed-duration render cost.
inline pipelines::RenderCost ms(double v) {
  pipelines::RenderCost::Params p;
  p.fixed_ms = v;
  return pipelines::RenderCost(p, 0, 0);
}

inline fs::StageSpec stage(const char* name, std::vector<int> procs, double dur_ms,
                           fs::StartRule rule = fs::StartRule::after, bool samples = false) {
  fs::StageSpec s;
  s.name = name;
  s.processors = std::move(procs);
  s.cost = ms(dur_ms);
  s.start = rule;
  s.samples_pose = samples;
  return s;
}

inline fs::StageSpec streaming(const char* name, std::vector<int> procs, double dur_ms, double lag_ms) {
  fs::StageSpec s = stage(name, std::move(procs), dur_ms, fs::StartRule::stream);
  s.lag = des::Time::from_ms(lag_ms);
  return s;
}

/// The reference display: 62.5 Hz (16 ms), progressive, no blanking, 160
/// lines of 0.1 ms, scanned out per line; a 1000 Hz tracker (or `tracker_hz`)
/// with sample 0 at t = 0, no delay, on a direct link; a head turning at 30 deg/s.
struct Rig {
  des::Simulator sim;
  tracker::ConstantAngularVelocity motion;
  tracker::Tracker tracker;
  tracker::DirectLink link;
  pipelines::TrackerHost host;
  display::Display display;
  pipelines::LatencyRecorder recorder;
  scenario::ScenarioDocument doc;
  std::unique_ptr<pipelines::RunContext> ctx;
  fs::FrameStagesPipeline pipeline;
  nlohmann::json figures;

  static tracker::TrackerParams tracker_params(int hz) {
    tracker::TrackerParams p;
    p.period = des::RationalSeconds::period_of_hz(hz);
    return p;
  }
  static display::RasterTiming timing() {
    display::RasterParams p;
    p.field_period = des::RationalSeconds::period_of_hz(125, 2);
    p.width_px = 16;
    p.height_px = 160;
    p.vblank_lines = 0;
    p.hblank_px = 0;
    return display::RasterTiming(p);
  }

  Rig(fs::FrameStagesSpec spec, int tracker_hz = 1000)
      : motion(tracker::Pose{}, glm::dvec3(0, 1, 0), 30.0),
        tracker(tracker_params(tracker_hz), motion, des::RandomStream(1, "tracker", 0)),
        host(sim, tracker, link),
        display(sim, timing(), 1, display::ScanoutFidelity::Line),
        recorder(sim, motion, host, display.timing(), pipelines::ProbeSet{}, 0.064, false, false),
        doc(scenario::ScenarioDocument::from_json(nlohmann::json::object(), ".")),
        pipeline(std::move(spec)) {
    display.add_listener(&recorder);
    ctx.reset(new pipelines::RunContext{sim, doc.root(), doc.root(), 1, 0, des::Time::zero(), motion, host, display,
                                        recorder, 0.064, false, nullptr, nullptr, {}});
  }

  /// Runs for `seconds` of simulated time and collects the pipeline's figures.
  void run(double seconds) {
    const des::Time end = des::Time::from_seconds(seconds);
    ctx->duration = end;
    host.start(end);
    display.start(end);
    pipeline.start(*ctx);
    sim.run_until(end);
    pipeline.finish(*ctx, figures);
  }

  double mtp(const char* stat) const {
    const auto* d = recorder.distribution("motion_to_photon_ms");
    return stat[1] == 'i' ? d->summary().min : d->summary().max;
  }
};

}  // namespace latsim::testing
