#include "latsim/run/builder.hpp"

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <stdexcept>

#include "built_from.hpp"
#include "latsim/des/stop_token.hpp"
#include "latsim/run/builtin_pipelines.hpp"
#include "latsim/tracker/motion_and_transport.hpp"
#include "latsim/units/units.hpp"

namespace latsim::run {

using namespace results;
using pipelines::RunContext;
using Json = nlohmann::json;

namespace {

/// A ring of points 2 m around the start position, every 15 degrees of yaw at
/// three heights, so that some are in view whatever the head does.
ProbeSet default_probes(const tracker::Pose& start, double hfov_deg) {
  ProbeSet p;
  p.hfov_deg = hfov_deg;
  for (int i = 0; i < 24; ++i)
    for (int k = -1; k <= 1; ++k) {
      const double yaw = units::deg_to_rad(i * 15.0), pitch = units::deg_to_rad(k * 15.0);
      const glm::dvec3 dir(-std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch));
      p.points_m.push_back(start.position_m + 2.0 * dir);
    }
  return p;
}

// Every clock of the shared models gets the phase the scenario fixes or one
// drawn for this replication. The parameters keep the nominal periods; the
// display's raster is built with the display clock's actual period (the
// tracker and the link apply their rate errors themselves).
// Phase luck. A tracker and a display on exact, commensurate clocks whose
// periods are in the ratio a/b (lowest terms) meet in only b relative
// phases, T_tracker / b apart, for the whole run: the age of the sample a
// refresh finds (and every latency built on it) is one draw of where those b
// phases sit. Another replication draws other phases and can move the run's
// mean latency by up to T_tracker / b. Said when both phases were drawn (a
// fixed phase is the user's choice), neither clock drifts (rate error,
// display clock noise) nor jitters, and the spread is at least 0.5 ms.
std::optional<std::string> phase_luck(const Run& run) {
  const sections::SharedParams& p = run.shared();
  const des::Clock* tracker = run.clocks->find("tracker");
  const des::Clock* display = run.clocks->find("display");
  if (!tracker || !display || !tracker->drawn || !display->drawn) return std::nullopt;
  if (tracker->rate_error_ppm != 0.0 || display->rate_error_ppm != 0.0 || p.display.clock_noise ||
      p.tracker.jitter > des::Time::zero())
    return std::nullopt;
  // T_display / T_tracker = (dn / dd) / (tn / td) = dn td / (dd tn), reduced.
  const auto gcd = [](unsigned __int128 x, unsigned __int128 y) {
    while (y != 0) {
      const unsigned __int128 r = x % y;
      x = y;
      y = r;
    }
    return x;
  };
  const auto dn = static_cast<unsigned __int128>(display->period.num), dd = static_cast<unsigned __int128>(display->period.den);
  const auto tn = static_cast<unsigned __int128>(tracker->period.num), td = static_cast<unsigned __int128>(tracker->period.den);
  const unsigned __int128 num = dn * td, den = dd * tn;
  const unsigned __int128 b = den / gcd(num, den);
  const double tracker_ms = tracker->period.to_seconds() * 1e3;
  const double spread_ms = tracker_ms / static_cast<double>(b);
  if (!(spread_ms >= 0.5)) return std::nullopt;
  char text[512];
  std::snprintf(text, sizeof text,
                "phase luck: the tracker (%.6g Hz) and the display (%.6g Hz) run on exact, commensurate clocks with "
                "phases drawn for this replication, so every refresh finds the tracker at one of %llu phase%s for the "
                "whole run: its latency figures can move by up to %.3g ms with the phases drawn; replications (a "
                "sweep with \"axes\": [] and \"replications\") give their mean and spread, or fix "
                "/tracker/phase_ms and /display/phase_ms",
                1e3 / tracker_ms, 1.0 / display->period.to_seconds(), static_cast<unsigned long long>(b),
                b == 1 ? "" : "s", spread_ms);
  return std::string(text);
}

// Every clock of the run is resolved here, once: the phase each model runs
// on is the resolved clock's (RunClocks), never written back into the bound
// scenario, which stays as the scenario file and the defaults make it.
void resolve_clocks(Run& run, uint64_t replication) {
  const sections::SharedParams& p = run.shared();
  run.clocks = std::make_unique<des::RunClocks>(run.seed, replication);
  // A rate error that leaves a period no 64-bit fraction holds is the scenario's problem, at its key.
  auto resolve = [&run](const char* name, const std::string& prefix, des::RationalSeconds period,
                        const des::ClockSettings& settings) -> const des::Clock& {
    try {
      return run.clocks->resolve(name, prefix + "phase_ms", period, settings);
    } catch (const std::invalid_argument& e) {
      throw scenario::ScenarioError(prefix + "rate_error_ppm", e.what());
    }
  };
  resolve("tracker", "/tracker/", p.tracker.period, p.tracker.clock);
  const tracker::SerialLinkParams& serial = p.transport.serial;
  if (p.transport.type == tracker::TransportParams::Type::Serial && serial.host_mode == tracker::SerialLinkParams::Poll)
    resolve("poll", "/transport/poll_", tracker::exact_period(serial.poll_interval), serial.poll_clock);
  if (p.transport.type == tracker::TransportParams::Type::UsbHid)
    resolve("usb_poll", "/transport/poll_", des::RationalSeconds{1, p.transport.usb.poll_hz}, p.transport.usb.poll_clock);
  if (p.tracker.imu && p.tracker.imu->reference)
    resolve("reference", "/tracker/imu/reference/", p.tracker.imu->reference->period, p.tracker.imu->reference->clock);
  if (p.controller && p.controller->tracker) {
    const tracker::TrackerParams& c = *p.controller->tracker;
    resolve("controller", "/controller/tracker/", c.period, c.clock);
    if (c.imu && c.imu->reference)
      resolve("controller_reference", "/controller/tracker/imu/reference/", c.imu->reference->period,
              c.imu->reference->clock);
    const tracker::TransportParams& link = p.controller->transport;
    if (link.type == tracker::TransportParams::Type::UsbHid)
      resolve("controller_usb_poll", "/controller/transport/poll_", des::RationalSeconds{1, link.usb.poll_hz},
              link.usb.poll_clock);
  }
  resolve("display", "/display/", p.display.raster.field_period, p.display.clock);
  if (p.measurement) resolve("camera", "/measurement/", p.measurement->frame_period, p.measurement->clock);
}

// A tracker's parameters with the clocks the run resolved for its reports
// and its reference: the models read their clocks from their parameters.
tracker::TrackerParams tracker_as_resolved(const Run& run, tracker::TrackerParams t, const char* reports,
                                           const char* reference) {
  t.clock = run.clocks->find(reports)->settings();
  if (t.imu && t.imu->reference) t.imu->reference->clock = run.clocks->find(reference)->settings();
  return t;
}

// A link's parameters with the poll clocks the run resolved for it (those it has).
tracker::TransportParams transport_as_resolved(const Run& run, tracker::TransportParams t, const char* serial_poll,
                                               const char* usb_poll) {
  if (const des::Clock* c = serial_poll ? run.clocks->find(serial_poll) : nullptr) t.serial.poll_clock = c->settings();
  if (const des::Clock* c = run.clocks->find(usb_poll)) t.usb.poll_clock = c->settings();
  return t;
}

// The display clock's jitter and wander for every field of the run (and a
// few beyond), from the run's stream "display.clock_noise".
std::shared_ptr<const display::ClockNoise> clock_noise(const display::RasterTiming& timing,
                                                       const display::ClockNoiseParams& params, const Run& run,
                                                       const RunOptions& options) {
  const des::Time slack = timing.end_slack();
  const std::string at = "/display/clock_noise/jitter_ns_rms";
  if (params.jitter_rms * 16 > slack)
    throw scenario::ScenarioError(at, "four standard deviations of jitter must fit in a quarter of the blank time after "
                                      "a field's last pixel (" + slack.str() + "): a field would start before the "
                                      "previous one was lit; lower the jitter or widen hblank_px");
  const int64_t fields = timing.field_at_or_after(run.duration) + 16;
  return std::make_shared<const display::ClockNoise>(params, timing.params().field_period, slack, fields,
                                                     des::RandomStream(run.seed, "display.clock_noise",
                                                                       options.replication));
}

// The controller's own chain: its tracker (IMU and reports), its link, the
// runtime's fusion of it and a predictor of /host/prediction's settings.
void track_controller_chain(Run& run, const RunOptions& options) {
  const sections::ControllerParams& c = *run.shared().controller;
  const des::RandomStream stream(run.seed, "controller", options.replication);
  const tracker::TrackerParams chain = tracker_as_resolved(run, *c.tracker, "controller", "controller_reference");
  auto device = std::make_unique<tracker::Tracker>(chain, *run.controller_motion, stream.substream("tracker"));
  auto link = tracker::make_transport(transport_as_resolved(run, c.transport, nullptr, "controller_usb_poll"),
                                      stream.substream("transport"));
  std::unique_ptr<tracker::RuntimeFusion> fusion;
  if (chain.imu)
    fusion = std::make_unique<tracker::RuntimeFusion>(*chain.imu, *run.controller_motion, stream.substream("reference"));
  const tracker::PredictionParams prediction = run.shared().host.prediction.value_or(tracker::PredictionParams{});
  run.host->track_controller(std::make_unique<DeviceFeed>(run.sim, std::move(device), std::move(link),
                                                          std::move(fusion), prediction, "controller"));
}

}  // namespace

ProbeSet probes_of(const Run& run) {
  const double hfov_deg = run.shared().display.hfov_deg;
  if (!run.shared().probes) return default_probes(run.motion->pose_at(des::Time::zero()), hfov_deg);
  return ProbeSet{run.shared().probes->points_m, hfov_deg};
}

void build(Run& run, const scenario::ScenarioDocument& doc, const RunOptions& options) {
  build(run, BoundScenario::of(doc, options.pipelines), options);
}

void build(Run& run, std::shared_ptr<const BoundScenario> bound, const RunOptions& options) {
  run.bound = std::move(bound);
  const sections::SharedParams& p = run.shared();
  run.duration = des::Time::from_seconds(p.duration_s);
  run.seed = options.seed ? *options.seed : static_cast<uint64_t>(p.seed);
  resolve_clocks(run, options.replication);
  // A run that could never finish is refused before anything is built.
  built_from("/pipeline", "pipeline", [&] {
    run.pipeline = run.bound->make_pipeline();
    run.estimate = estimate_events(p, *run.pipeline);
  });
  check_event_budget(run.estimate, options.max_events);
  built_from("/motion", "head motion", [&] { run.motion = tracker::make_motion(p.motion); });
  built_from("/tracker", "tracker", [&] {
    run.tracker = std::make_unique<tracker::Tracker>(tracker_as_resolved(run, p.tracker, "tracker", "reference"),
                                                     *run.motion,
                                                     des::RandomStream(run.seed, "tracker", options.replication));
  });
  built_from("/transport", "transport", [&] {
    run.transport = tracker::make_transport(transport_as_resolved(run, p.transport, "poll", "usb_poll"),
                                            des::RandomStream(run.seed, "transport", options.replication));
  });
  Timeline* timeline = p.output.timeline && options.write_timeline ? &run.timeline : nullptr;
  run.timeline.set_max_entries(static_cast<size_t>(p.output.timeline_max_entries));
  run.host = std::make_unique<TrackerHost>(run.sim, *run.tracker, *run.transport, timeline, p.host.prediction);
  if (p.tracker.imu)
    built_from("/tracker/imu", "tracking chain", [&] {
      run.host->fuse_with(std::make_unique<tracker::RuntimeFusion>(
          *run.tracker->params().imu, *run.motion, des::RandomStream(run.seed, "reference", options.replication)));
    });
  if (p.controller) {
    built_from("/controller/motion", "controller motion",
               [&] { run.controller_motion = tracker::make_motion(p.controller->motion); });
    if (p.controller->tracker)
      built_from("/controller/tracker", "controller's tracking chain", [&] { track_controller_chain(run, options); });
    else
      run.host->track_controller(*run.controller_motion,
                                 des::RandomStream(run.seed, "controller", options.replication).substream("noise"));
  }
  const bool stereo = p.host.stereo;
  built_from("/display", "display", [&] {
    display::RasterParams raster = p.display.raster;
    raster.field_period = run.clocks->find("display")->period;
    display::RasterTiming timing(raster, run.clocks->find("display")->phase);
    if (p.display.clock_noise) timing.set_clock_noise(clock_noise(timing, *p.display.clock_noise, run, options));
    run.display = std::make_unique<display::Display>(run.sim, timing, stereo ? 2 : 1, p.display.fidelity,
                                                     p.display.pixel_stride, p.display.pixel_events);
  });
  built_from("/probes", "registration probes", [&] {
    run.recording = std::make_unique<RunRecording>(run.sim, *run.motion, *run.host, run.images, run.display->timing(),
                                                   probes_of(run), p.host.ipd_m, stereo, p.output.keep_samples);
  });
  RunRecording& rec = *run.recording;
  for (const auto& w : run.bound->input_warnings()) rec.book().warn(w);
  if (auto luck = phase_luck(run)) rec.book().warn(*luck);
  rec.prediction().enable(p.host.prediction.has_value());
  if (p.motion_phases) rec.split_by_phase(*p.motion_phases);
  if (p.apparent_latency)
    rec.seen().measure_apparent_latency(*p.apparent_latency, p.motion_phases.value_or(tracker::MotionPhaseParams{}));
  if (p.measurement) rec.seen().film(*p.measurement, run.clocks->find("camera")->schedule());
  if (run.controller_motion) rec.seen().track_controller(*run.controller_motion);
  rec.keep_ledger(options.write_ledger);
  rec.keep_sample_log(options.write_samples);
  run.display->add_listener(&rec.scanout());
  if (p.display.persistence) {
    run.display->set_persistence(*p.display.persistence);
    rec.registration().set_persistence(&run.display->persistence());
    rec.seen().set_persistence(&run.display->persistence());
    run.smear = std::make_unique<SmearRecorder>(rec.book().writer("smear"), *run.motion);
    run.display->add_listener(run.smear.get());
  }
  run.files = RunFiles(options.out_dir, options.staging_dir);
  run.files.set_write_images(options.write_images);
  if (p.frames && p.frames->enabled) {
    built_from("/frames", "frame capture", [&] {
      run.frames = std::make_unique<FrameCapture>(
          *p.frames, p.scene ? p.scene->geometry : renderer::SceneSpec{},
          FrameCaptureInputs{run.images, rec.book().writer("frame capture"), *run.host, *run.motion,
                             run.display->timing(), p.display.hfov_deg, p.host.ipd_m, stereo, run.files,
                             p.display.persistence ? &run.display->persistence() : nullptr});
    });
    run.display->add_listener(run.frames.get());
  }
  rec.images().set_timeline(timeline);
  if (timeline) {
    // The display's own track: each field's vertical blank and active
    // scanout, from the retraces the display really makes (phase included).
    const display::RasterTiming* timing = &run.display->timing();
    run.display->on_retrace([timeline, timing](int64_t field, des::Time retrace) {
      const des::Time scanout = timing->scanout_start(field);
      if (scanout > retrace) timeline->add("VBLANK", field, -1, "display", retrace, scanout);
      timeline->add("SCANOUT", field, -1, "display", scanout, timing->field_start(field + 1));
    });
  }
  rec.scanout().set_frame_recorder(&run.app_frames);
  const bool line = run.transport->occupancy() > des::Time::zero();
  results::LinkFigures* link = &rec.link();
  run.host->on_carried([link, line](const tracker::TrackerSample& s, const tracker::Carriage& c) {
    link->record_carried(s, c, line);
  });

  built_from("/pipeline", "pipeline", [&] {
    run.ctx = std::unique_ptr<RunContext>(new RunContext{
        run.sim, run.seed, options.replication, run.duration, *run.motion, run.tracker->params(), *run.transport, *run.host,
        *run.display, p.display, p.scene ? &*p.scene : nullptr, run.images, rec.pipeline_figures(), rec.signals(),
        run.app_frames, run.files, *run.clocks, p.host.ipd_m,
        stereo, timeline, run.frames.get()});
    run.pipeline->start(*run.ctx);
  });
}

Json resolved_scenario(const Run& run) {
  Json resolved = run.bound->doc().resolved();
  // The phases used, drawn or fixed, make the resolved scenario reproduce this
  // run: read from the run's clocks, where they were decided.
  for (const auto& [pointer, ms] : run.clocks->phases_ms()) resolved[Json::json_pointer(pointer)] = ms;
  return resolved;
}

}  // namespace latsim::run
