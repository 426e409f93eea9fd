// Bindings of an IMU tracking chain (/tracker/imu, /controller/tracker/imu):
// the gyroscope, its reports, the external reference and the runtime's fusion.
#include "latsim/sections/shared.hpp"

namespace latsim::sections {

using scenario::Section;

namespace {

void gyro(Section& s, tracker::ImuParams& g) {
  s.number("gyro_noise_density_deg_s_rthz", g.gyro_noise_density_deg_s_rthz,
           {.unit = "deg/s/√Hz", .min = 0.0, .max = 1e3,
            .doc = "white rate noise (angle random walk): a reading at rate f has a per-axis standard deviation of "
                   "this × √f"});
  s.number("gyro_bias_deg_s", g.gyro_bias_deg_s,
           {.unit = "deg/s", .min = 0.0, .max = 1e3,
            .doc = "residual bias after calibration: per axis, drawn once per replication (normal, this standard "
                   "deviation)"});
  s.number("bias_instability_deg_s", g.bias_instability_deg_s,
           {.unit = "deg/s", .min = 0.0, .max = 1e3,
            .doc = "bias wander: a first-order Gauss-Markov process of this standard deviation per axis (0: none)"});
  s.duration("bias_correlation_s", g.bias_correlation,
             {.unit = "s", .min = 0.0, .max = 1e6, .above_min = true, .doc = "correlation time of the bias wander"});
  s.duration("timestamp_tick_us", g.timestamp_tick,
             {.unit = "us", .min = 0.0, .max = 1e6,
              .doc = "the device clock's tick: each reading's timestamp is a whole number of ticks (0: exact)"});
  s.number("range_deg_s", g.range_deg_s,
           {.unit = "deg/s", .min = 0.0, .max = 1e6, .above_min = true, .doc = "readings saturate at ±this per axis"});
}

void reference(Section& s, tracker::ReferenceParams& r) {
  s.doc(
      "The absolute reference that corrects the gyroscope: Lighthouse sweeps or inside-out camera frames, one "
      "complete pose per period, known to the fusion `latency_ms` after it was measured.");
  s.rate("rate_hz", r.period, {.unit = "Hz", .doc = "complete poses per second (exact rational)"});
  clock(s, "", r.clock, "reference");
  s.duration("latency_ms", r.latency,
             {.unit = "ms", .max = 1e6, .doc = "from the measurement to the fusion having it"});
  s.number("orientation_stddev_deg", r.orientation_stddev_deg,
           {.unit = "deg", .min = 0.0, .max = 180.0, .doc = "orientation noise of a fix, per axis"});
  s.number("position_stddev_m", r.position_stddev_m,
           {.unit = "m", .min = 0.0, .max = 1e3, .doc = "position noise of a fix, per axis"});
}

void fusion(Section& s, tracker::FusionParams& f) {
  s.doc(
      "The runtime's complementary filter: the gyroscope integrated, each fix pulling the orientation by "
      "1 − exp(−Δt/τ) of the error it measures, the bias estimated from what the fixes correct (docs/devices.md).");
  s.duration("orientation_time_constant_ms", f.orientation_time_constant,
             {.unit = "ms", .min = 0.0, .max = 1e9, .above_min = true,
              .doc = "τ: how fast fixes pull the orientation (smaller: more of the reference's noise)"});
  s.duration("bias_time_constant_s", f.bias_time_constant,
             {.unit = "s", .min = 0.0, .max = 1e6, .doc = "how fast fixes correct the gyro bias (0: not estimated)"});
  s.flag("align_reference", f.align_reference,
         {.doc = "compare each fix with the orientation the filter had when it was measured (false: with its "
                 "newest one, so a delayed fix drags a turning estimate back)"});
  s.duration("history_ms", f.history,
             {.unit = "ms", .min = 0.0, .max = 1e6, .above_min = true,
              .doc = "how far back the filter keeps its orientations for aligning fixes"});
  s.integer("rate_readings", f.rate_readings,
            {.min = 1.0, .max = 1000.0, .doc = "the angular velocity reported is the mean of this many newest readings"});
}

}  // namespace

void bind(Section& s, tracker::ImuChainParams& p) {
  s.doc(
      "Tracking as a headset does it: the tracker's samples are gyroscope readings at /tracker/rate_hz, carried "
      "in reports to the host, where the runtime fuses them with an external reference; the host's pose and its "
      "angular velocity are the fusion's (docs/devices.md). /tracker/jitter_ms and /tracker/noise are not used.");
  gyro(s, p.gyro);
  s.integer("samples_per_report", p.samples_per_report,
            {.min = 1.0, .max = 64.0, .doc = "each report carries the newest this many readings"});
  s.integer("report_every", p.report_every,
            {.min = 1.0, .max = 1000.0, .doc = "readings between two reports (the report interval in readings)"});
  s.number("report_loss_probability", p.report_loss_probability,
           {.min = 0.0, .max = 0.99, .doc = "chance that a report never reaches the host (independent per report)"});
  s.optional_object("reference", p.reference, reference, {.doc = "the external reference (none: the gyro alone)"});
  s.object("fusion", p.fusion, fusion, {.doc = "the runtime's fusion of gyro and reference"});
}

void bind_controller_chain(Section& s, ControllerParams& p) {
  s.optional_object("tracker", p.tracker, [](Section& t, tracker::TrackerParams& v) { bind(t, v); },
                    {.doc = "the controller's own tracking chain, as /tracker (absent: measured with every head "
                            "sample, with the tracker's noise)"});
  s.object("transport", p.transport, [](Section& t, tracker::TransportParams& v) { bind(t, v); },
           {.doc = "the controller's link to the host (read with /controller/tracker): its radio and the "
                   "receiver's USB poll"});
  if (s.describing()) return;
  s.check("transport", p.tracker || !s.has("transport"), "a controller link needs /controller/tracker");
  s.check("transport", p.transport.type != tracker::TransportParams::Type::Serial,
          "a controller's link cannot be a serial line (records would wait in a buffer of the head's)");
}

}  // namespace latsim::sections
