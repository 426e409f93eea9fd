// Builds the shared models by hand around a frame_stages pipeline given as a
// spec, so that the engine is tested without a scenario file.
#pragma once

#include <memory>
#include <optional>

#include "frame_stages/frame_stages_pipeline.hpp"
#include "latsim/des/run_clocks.hpp"
#include "latsim/des/simulator.hpp"
#include "latsim/display/display.hpp"
#include "latsim/display/params.hpp"
#include "latsim/results/frame_recorder.hpp"
#include "latsim/results/image_book.hpp"
#include "latsim/results/latency_recorder.hpp"
#include "latsim/results/run_files.hpp"
#include "latsim/results/smear_recorder.hpp"
#include "latsim/run/tracker_host.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::testing {

namespace fs = pipelines::frame_stages;

/// Fixed-duration render cost.
inline renderer::RenderCost ms(double v) {
  renderer::RenderCost::Params p;
  p.fixed_ms = v;
  return renderer::RenderCost(p, 0, 0);
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

/// What a rig is built with; the defaults are the reference system: a
/// 62.5 Hz (16 ms) progressive display without blanking, 160 lines of 0.1 ms
/// scanned out per line; a 1000 Hz tracker with sample 0 at t = 0 and no
/// delay on a direct link; a head turning at 30 deg/s.
struct RigOptions {
  int tracker_hz = 1000;
  des::RationalSeconds field_period = des::RationalSeconds::period_of_hz(125, 2);
  int lines = 160;
  std::shared_ptr<tracker::MotionSource> motion =
      std::make_shared<tracker::ConstantAngularVelocity>(tracker::Pose{}, glm::dvec3(0, 1, 0), 30.0);
  std::optional<display::PersistenceParams> persistence;  ///< none: lit at the scanout instant
};

/// A head walking along +x at `speed_m_s`, looking ahead (no rotation).
inline std::shared_ptr<tracker::MotionSource> walking(double speed_m_s) {
  tracker::WalkParams w;
  w.points_m = {glm::dvec3(0, 1.6, 0), glm::dvec3(1000, 1.6, 0)};
  w.speed_m_s = speed_m_s;
  return std::make_shared<tracker::PolylineWalk>(w);
}

/// The shared models around one frame_stages pipeline.
struct Rig {
  des::Simulator sim;
  std::shared_ptr<tracker::MotionSource> motion;
  tracker::TrackerParams tracker_params;
  tracker::Tracker tracker;
  tracker::DirectLink link;
  run::TrackerHost host;
  display::DisplayParams display_params;
  display::Display display;
  results::ImageBook images;
  results::LatencyRecorder recorder;
  results::FrameRecorder app_frames;
  results::RunFiles files;
  des::RunClocks clocks{1, 0};
  std::unique_ptr<pipelines::RunContext> ctx;
  fs::FrameStagesPipeline pipeline;
  std::unique_ptr<results::SmearRecorder> smear;
  nlohmann::json figures;

  static tracker::TrackerParams tracker_of(int hz) {
    tracker::TrackerParams p;
    p.period = des::RationalSeconds::period_of_hz(hz);
    return p;
  }
  static display::DisplayParams display_of(const RigOptions& o) {
    display::DisplayParams d;
    display::RasterParams& p = d.raster;
    p.field_period = o.field_period;
    p.width_px = 16;
    p.height_px = o.lines;
    p.vblank_lines = 0;
    p.hblank_px = 0;
    d.fidelity = display::ScanoutFidelity::Line;
    d.persistence = o.persistence;
    return d;
  }

  explicit Rig(fs::FrameStagesSpec spec, RigOptions o = {})
      : motion(o.motion),
        tracker_params(tracker_of(o.tracker_hz)),
        tracker(tracker_params, *motion, des::RandomStream(1, "tracker", 0)),
        host(sim, tracker, link),
        display_params(display_of(o)),
        display(sim, display::RasterTiming(display_params.raster), 1, display_params.fidelity),
        recorder(sim, *motion, host, images, display.timing(), results::ProbeSet{}, 0.064, false, false),
        pipeline(fs::FrameStagesPipeline::Params{std::move(spec)}) {
    display.add_listener(&recorder);
    if (o.persistence) {
      display.set_persistence(*o.persistence);
      recorder.set_persistence(&display.persistence());
      smear = std::make_unique<results::SmearRecorder>(recorder, *motion);
      display.add_listener(smear.get());
    }
    ctx.reset(new pipelines::RunContext{sim, 1, 0, des::Time::zero(), *motion, tracker_params, link, host, display,
                                        display_params, nullptr, images, recorder, app_frames, files, clocks, 0.064, false, nullptr,
                                        nullptr});
  }

  /// Runs for `seconds` of simulated time and collects the pipeline's figures.
  void run(double seconds) {
    const des::Time end = des::Time::from_seconds(seconds);
    ctx->duration = end;
    host.start(end);
    display.start(end);
    pipeline.start(*ctx);
    sim.run_until(end);
    pipeline.finish(*ctx);
    app_frames.finish(recorder, end);
    figures = recorder.figures();
  }

  /// A summary statistic ("min", "max", "mean", "count") of a recorded distribution.
  double stat(const char* name, const std::string& which) const {
    const auto* d = recorder.distribution(name);
    if (d == nullptr) return -1.0;
    const auto s = d->summary();
    if (which == "min") return s.min;
    if (which == "max") return s.max;
    if (which == "count") return static_cast<double>(s.count);
    return s.mean;
  }
  double mtp(const char* which) const { return stat("motion_to_photon_ms", which); }
};

}  // namespace latsim::testing
