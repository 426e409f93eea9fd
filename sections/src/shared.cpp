#include "latsim/sections/shared.hpp"

#include <cmath>

namespace latsim::sections {

using scenario::KeySpec;
using scenario::Section;

void vec3(Section& s, std::string_view key, glm::dvec3& v, KeySpec spec) {
  std::vector<double> xyz{v.x, v.y, v.z};
  spec.count = 3;
  s.numbers(key, xyz, spec);
  v = glm::dvec3(xyz[0], xyz[1], xyz[2]);
}

void colour(Section& s, std::string_view key, glm::vec3& v, KeySpec spec) {
  std::vector<double> rgb{v.r, v.g, v.b};
  spec.count = 3;
  s.numbers(key, rgb, spec);
  v = glm::vec3(static_cast<float>(rgb[0]), static_cast<float>(rgb[1]), static_cast<float>(rgb[2]));
}

void clock(Section& s, std::string_view prefix, des::ClockSettings& c, std::string_view what) {
  const std::string phase_key = std::string(prefix) + "phase_ms";
  const std::string rate_key = std::string(prefix) + "rate_error_ppm";
  const std::string phase_doc = "time of the " + std::string(what) + "'s first tick";
  const std::string rate_doc = "the " + std::string(what) +
                               "'s frequency error (crystals: tens of ppm); positive runs fast";
  s.duration(phase_key, c.phase,
             {.unit = "ms", .doc = phase_doc,
              .default_doc = "drawn per replication, uniform over one period, from the clock's own stream"});
  s.number(rate_key, c.rate_error_ppm, {.unit = "ppm", .min = -1e5, .max = 1e5, .doc = rate_doc});
}

namespace {

void bind_host(Section& s, HostParams& p, const tracker::TrackerParams& tracker) {
  s.doc("The application's view of the head: one eye or two, and whether it predicts the pose.");
  s.flag("stereo", p.stereo, {.doc = "two eyes, two synchronised displays"});
  s.number("ipd_m", p.ipd_m,
           {.unit = "m", .min = 0.0, .max = 1.0, .doc = "inter-pupillary distance (eyes ±ipd/2 along the head's x axis)"});
  s.optional_object("prediction", p.prediction,
                    [&tracker](Section& q, tracker::PredictionParams& v) { bind(q, v, tracker); },
                    {.doc = "pose prediction (none when absent)"});
}

void bind_probes(Section& s, ProbeParams& p) {
  s.doc(
      "World points whose registration error is measured on every field they are drawn in. Without this section: "
      "a ring 2 m around the start position, every 15° of yaw at −15°, 0° and +15° of pitch.");
  std::vector<std::vector<double>> rows;
  s.number_rows("points_m", rows,
                {.unit = "m", .min = -1e6, .max = 1e6, .count = 3, .required = true, .doc = "world points [[x, y, z], …]"});
  p.points_m.clear();
  for (const auto& r : rows) p.points_m.emplace_back(r[0], r[1], r[2]);
}

void bind_output(Section& s, OutputParams& p) {
  s.doc(
      "What a run keeps besides its figures. `latsim run` writes `summary.json` (last, atomically), `figures.json` "
      "(byte-identical for the same scenario and seed), `timeline.csv`/`.json` where a pipeline keeps one, "
      "`presentmon.csv` where it has application frames (unless `--no-presentmon`), `frames.csv` with `--ledger`, `samples.csv` with `--samples`, and `frames/` when the scenario asks for "
      "captures. Each distribution is `{count, mean, stddev, min, p50, p90, p99, p999, max, histogram}` in the "
      "unit of its name; `warnings` lists legal but doubtful input.");
  s.flag("keep_samples", p.keep_samples, {.doc = "keep every sample for exact quantiles (memory grows with the run)"});
  s.flag("timeline", p.timeline,
         {.doc = "keep the stage timeline (timeline.csv, timeline.json) when a pipeline writes one"});
  s.integer("timeline_max_entries", p.timeline_max_entries,
            {.min = 0.0, .max = 1099511627776.0, .doc = "entries kept; later ones are counted, not kept (0: all)"});
}

void bind_frames(Section& s, FramesParams& p, const HostParams& host) {
  s.doc(
      "Actual images next to the numbers: the chosen fields of one eye are ray-cast as displayed, as the truth at "
      "each row's photon time, their difference and the age of every pixel, written to `frames/` (see "
      "docs/frames.md). They show the `scene` (the default gallery when there is none).");
  s.flag("enabled", p.enabled, {.doc = "false keeps the settings but casts nothing"});
  s.numbers("at_s", p.at_s, {.unit = "s", .min = 0.0, .max = 1e6, .doc = "capture the first field at or after each time"});
  s.integer("every_nth_refresh", p.every_nth_refresh,
            {.min = 0.0, .max = 1099511627776.0, .doc = "also capture every n-th field (0: none)"});
  s.integer("max_captures", p.max_captures, {.min = 0.0, .max = 100000.0, .doc = "captures at most"});
  s.integer("eye", p.eye, {.min = 0.0, .max = 1.0, .doc = "which eye is captured (1: the right eye of a stereo display)"});
  s.integer("threads", p.threads, {.min = 1.0, .max = 256.0, .doc = "ray-casting threads (images do not depend on it)"});
  colour(s, "background", p.background, {.doc = "linear colour [r, g, b] where nothing is hit or lit"});
  s.number("diff_gain", p.diff_gain, {.min = 0.0, .above_min = true, .doc = "gain of the difference image"});
  s.number("age_scale_ms", p.age_scale_ms,
           {.unit = "ms", .min = 0.0, .above_min = true, .doc = "pixel age shown at full scale in the age heat map"});
  s.check("at_s", !(p.at_s.empty() && p.every_nth_refresh == 0),
          "say which fields to capture: \"at_s\": [seconds, ...] and/or \"every_nth_refresh\": N");
  s.check("eye", !(p.eye == 1 && !host.stereo), "eye 1 exists only on a stereo display (/host/stereo)");
}

// Interrupt handlers slower than the characters they serve back up without
// end, the backlog carried from record to record: the run's last record
// waits for the handlers of every record before it. Their total, like any
// span a scenario implies, must fit the 1e6 s a run may last (a cost of 1e12
// us passed the per-record check and overflowed simulated time mid-run).
void check_interrupt_backlog(Section& s, const SharedParams& p) {
  const tracker::SerialLinkParams& serial = p.transport.serial;
  if (s.describing() || p.transport.type != tracker::TransportParams::Type::Serial ||
      serial.host_mode != tracker::SerialLinkParams::Interrupt)
    return;
  const double records = std::ceil(p.duration_s / p.tracker.period.to_seconds());
  scenario::check_span_at("/transport/per_char_interrupt_us", serial.per_char_interrupt_cost.to_seconds(),
                          static_cast<double>(serial.record_bytes) * records,
                          "record_bytes × the run's records (duration_s × /tracker/rate_hz)");
}

}  // namespace

void bind(Section& s, SharedParams& p) {
  s.doc(
      "A scenario is one JSON object. Every key below is optional unless marked **required**; the default is what "
      "the run uses (and writes into the resolved scenario in `summary.json`). Any key latsim does not know is an "
      "error (`file: /json/pointer: unknown key`), so a misspelt key never goes unnoticed; a known key that the "
      "chosen mode of its object does not read (a poll interval on an interrupt-driven line) is a warning. "
      "Frequencies may be numbers (`60`) or exact fractions as strings (`\"60000/1001\"`); durations are in the "
      "unit their name says. The JSON Schema of this reference is printed by `latsim schema`.");
  s.text("description", p.description, {.doc = "free text, copied into the results"});
  s.number("duration_s", p.duration_s,
           {.unit = "s", .min = 0.0, .max = 1e6, .above_min = true,
            .doc = "simulated time (int64 picoseconds cover ±9.2e6 s)"});
  s.integer("seed", p.seed, {.min = 0.0, .doc = "run seed; every model draws from its own named stream derived from it"});
  s.object("motion", p.motion, [](Section& m, tracker::MotionParams& v) { bind(m, v); },
           {.required = true, .doc = "the true head motion"});
  s.optional_object("controller", p.controller,
                    [](Section& c, ControllerParams& v) {
                      c.doc("A handheld controller. Without /controller/tracker the tracker measures it at every head "
                            "sample's instant (with the tracker's noise, drawn from a stream of its own) and the "
                            "head's record carries it; with it, the controller has a chain of its own (its IMU, its "
                            "reports, its link /controller/transport, the runtime's fusion), and each image draws the "
                            "newest controller report the host had when the image's head pose was read. The host "
                            "predicts it with a predictor of its own of /host/prediction's settings to the image's "
                            "photon time. Re-projection (time warp) moves the view, not the controller: it stays "
                            "where the render drew it. Its figures are `controller_latency_ms` and, with "
                            "/apparent_latency, `controller_apparent_latency_ms` (docs/figures.md); "
                            "/measurement/object can film it.");
                      c.object("motion", v.motion, [](Section& m, tracker::MotionParams& mp) { bind(m, mp); },
                               {.required = true,
                                .doc = "the controller's true motion: the types of /motion (whose texts speak of the "
                                       "head)"});
                      bind_controller_chain(c, v);
                    },
                    {.doc = "a tracked handheld controller drawn by the pipeline (none when absent)"});
  s.object("tracker", p.tracker, [](Section& t, tracker::TrackerParams& v) { bind(t, v); },
           {.required = true, .doc = "sampling the head pose"});
  s.object("transport", p.transport, [](Section& t, tracker::TransportParams& v) { bind(t, v); },
           {.doc = "the link from tracker to host"});
  check_interrupt_backlog(s, p);
  const tracker::TrackerParams& tracker = p.tracker;
  s.object("host", p.host, [&tracker](Section& h, HostParams& v) { bind_host(h, v, tracker); },
           {.doc = "the application's view of the head"});
  s.object("display", p.display, [](Section& d, display::DisplayParams& v) { bind(d, v); },
           {.required = true, .doc = "the raster and how finely it is simulated"});
  s.object("output", p.output, bind_output, {.doc = "what a run keeps"});
  s.optional_object("probes", p.probes, bind_probes, {.doc = "where registration error is measured"});
  s.optional_object("scene", p.scene, [](Section& c, SceneParams& v) { bind(c, v); },
                    {.doc = "workload and what frames show"});
  const HostParams& host = p.host;
  s.optional_object("frames", p.frames, [&host](Section& f, FramesParams& v) { bind_frames(f, v, host); },
                    {.doc = "captured images"});
  s.optional_object("motion_phases", p.motion_phases,
                    [](Section& m, tracker::MotionPhaseParams& v) { bind(m, v); },
                    {.doc = "figures split by motion phase (not split when absent)"});
  s.optional_object("apparent_latency", p.apparent_latency,
                    [](Section& a, measurement::ApparentLatencyParams& v) { bind(a, v); },
                    {.doc = "apparent latency (not computed when absent)"});
  const bool controller = p.controller.has_value();
  s.optional_object("measurement", p.measurement,
                    [controller](Section& m, measurement::CameraRigParams& v) {
                      bind(m, v, controller ? "" : "the controller is filmed only in a scenario with /controller");
                    },
                    {.doc = "a simulated camera measurement rig (none when absent)"});
}

}  // namespace latsim::sections
