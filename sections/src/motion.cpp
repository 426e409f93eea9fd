#include <algorithm>
#include <cmath>

#include "latsim/sections/shared.hpp"
#include "latsim/units/units.hpp"

namespace latsim::sections {

using scenario::KeySpec;
using scenario::ModeDecl;
using scenario::Section;

namespace {


// A head is somewhere in a building, a city at most: a kilometre-scale bound
// keeps positions where single-precision ray casting still resolves millimetres.
constexpr double kFarthestM = 1e6;

void start_position(Section& s, tracker::MotionParams& p) {
  vec3(s, "position_m", p.position_m, {.unit = "m", .min = -kFarthestM, .max = kFarthestM, .doc = "head position [x, y, z]"});
}

void start_orientation(Section& s, tracker::MotionParams& p) {
  s.number("yaw_deg", p.yaw_deg, {.unit = "deg", .doc = "starting yaw (positive turns left, about +y)"});
  s.number("pitch_deg", p.pitch_deg, {.unit = "deg", .min = -90.0, .max = 90.0, .doc = "starting pitch (positive looks up)"});
}

void constant(Section& s, tracker::MotionParams& p) {
  start_position(s, p);
  start_orientation(s, p);
  vec3(s, "axis", p.axis, {.doc = "rotation axis in world coordinates"});
  s.check("axis", p.axis != glm::dvec3(0.0), "the rotation axis must not be zero");
  s.number("rate_deg_s", p.rate_deg_s, {.unit = "deg/s", .doc = "angular speed (right-hand rule about the axis)"});
}

void sinusoid(Section& s, tracker::MotionParams& p) {
  tracker::SinusoidParams& q = p.sinusoid;
  start_position(s, p);
  q.position_m = p.position_m;
  s.number("yaw_amplitude_deg", q.yaw_amplitude_deg, {.unit = "deg", .doc = "yaw amplitude"});
  s.number("yaw_frequency_hz", q.yaw_frequency_hz, {.unit = "Hz", .min = 0.0, .doc = "yaw frequency"});
  s.number("yaw_phase_deg", q.yaw_phase_deg, {.unit = "deg", .doc = "yaw phase"});
  s.number("pitch_amplitude_deg", q.pitch_amplitude_deg, {.unit = "deg", .min = -90.0, .max = 90.0, .doc = "pitch amplitude"});
  s.number("pitch_frequency_hz", q.pitch_frequency_hz, {.unit = "Hz", .min = 0.0, .doc = "pitch frequency"});
  s.number("pitch_phase_deg", q.pitch_phase_deg, {.unit = "deg", .doc = "pitch phase"});
}

void minimum_jerk(Section& s, tracker::MotionParams& p) {
  tracker::MinimumJerkParams& m = p.minimum_jerk;
  start_position(s, p);
  start_orientation(s, p);
  s.number("amplitude_deg", m.amplitude_deg,
           {.unit = "deg", .min = -3600.0, .max = 3600.0, .doc = "angle of one movement about the axis"});
  s.duration("duration_s", m.duration,
             {.unit = "s", .min = 0.0, .max = 1e6, .above_min = true, .doc = "length of one movement"});
  s.duration("rest_s", m.rest, {.unit = "s", .min = 0.0, .max = 1e6, .doc = "stillness before each movement"});
  s.duration("delay_s", m.delay,
             {.unit = "s", .min = 0.0, .max = 1e6,
              .doc = "still for this long before the first rest (to place one motion's movements in another's rests)"});
  vec3(s, "axis", m.axis, {.doc = "rotation axis in world coordinates ([0, 1, 0]: yaw)"});
  s.check("axis", m.axis != glm::dvec3(0.0), "the rotation axis must not be zero");
  enum class Direction { Alternate, Same };
  Direction d = m.alternate ? Direction::Alternate : Direction::Same;
  s.choice("direction", d, {{"alternate", Direction::Alternate}, {"same", Direction::Same}},
           {.doc = "alternate: back and forth between the start and the amplitude; same: every movement turns further"});
  m.alternate = d == Direction::Alternate;
}

void walk(Section& s, tracker::MotionParams& p) {
  tracker::WalkParams& w = p.walk;
  std::vector<std::vector<double>> rows;
  s.number_rows("points", rows,
                {.unit = "m", .min = -kFarthestM, .max = kFarthestM, .count = 3, .required = true, .doc = "the path [[x, y, z], …]"});
  s.check("points", s.describing() || !rows.empty(), "a walk needs at least one point");
  w.points_m.clear();
  for (const auto& r : rows) w.points_m.emplace_back(r[0], r[1], r[2]);
  s.number("speed_m_s", w.speed_m_s, {.unit = "m/s", .min = 0.0, .above_min = true, .doc = "walking speed"});
  s.flag("loop", w.loop, {.doc = "return to the first point and go round again; false: stop at the end"});
  s.flag("face_direction", w.face_direction,
         {.doc = "look along the direction of travel; false: keep yaw_deg and pitch_deg"});
  s.number("turn_rate_deg_s", w.turn_rate_deg_s,
           {.unit = "deg/s", .min = 0.0, .max = 1e5,
            .doc = "facing the direction: yaw rate of the turn at each corner, centred on it (0: at once); 90 deg/s "
                   "turns a 90° corner in 1 s, over 1 m of walk at walking speed"});
  if (!w.face_direction || s.describing()) start_orientation(s, p);
  w.orientation = p.start_orientation();
}

void trace(Section& s, tracker::MotionParams& p) {
  s.path("file", p.trace_file,
         {.required = true,
          .doc = "recorded motion: latsim CSV `t_s,px,py,pz,qw,qx,qy,qz`, or the whitespace `timestamp viewpoint w x y "
                 "z` format of scenarios/data/"});
  s.guard("file", [&] { p.trace = std::make_shared<const tracker::Trace>(tracker::load_trace(p.trace_file)); });
  s.duration("offset_s", p.trace_offset, {.unit = "s", .min = -1e6, .max = 1e6, .doc = "trace time at t = 0"});
  s.flag("loop", p.trace_loop, {.doc = "start again at the end of the recording"});
}

void noise(Section& s, tracker::TrackerParams& p) {
  s.doc("Pose noise, sampled through the Cholesky factor of its covariance: give standard deviations or a covariance.");
  std::optional<std::vector<std::vector<double>>> covariance;
  s.number_rows("covariance", covariance,
                {.count = 6, .doc = "6x6 covariance: x, y, z in m², then the rotation vector in rad²"});
  s.check("covariance",
          !(covariance && (s.has("position_stddev_m") || s.has("orientation_stddev_deg"))),
          "give either a covariance or standard deviations, not both");
  tracker::NoiseCovariance c = tracker::NoiseCovariance::Zero();
  if (covariance) {
    s.check("covariance", covariance->size() == 6, "expected a 6x6 matrix (x, y, z, rx, ry, rz)");
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) c(i, j) = (*covariance)[static_cast<size_t>(i)][static_cast<size_t>(j)];
  }
  if (!covariance || s.describing()) {
    double position_m = 0.0, orientation_deg = 0.0;
    s.number("position_stddev_m", position_m, {.unit = "m", .min = 0.0, .doc = "position noise per axis"});
    s.number("orientation_stddev_deg", orientation_deg, {.unit = "deg", .min = 0.0, .doc = "orientation noise per axis"});
    const double orientation_rad = orientation_deg * units::kRadPerDeg;
    for (int i = 0; i < 3; ++i) c(i, i) = position_m * position_m;
    for (int i = 3; i < 6; ++i) c(i, i) = orientation_rad * orientation_rad;
  }
  p.noise_covariance = c;
  p.noise_enabled = !c.isZero(0.0);
  if (p.noise_enabled) s.guard("covariance", [&] { (void)tracker::noise_factor(p.noise_covariance); });
}

void serial(Section& s, tracker::SerialLinkParams& p) {
  s.integer("record_bytes", p.record_bytes, {.min = 1.0, .max = 1e6, .doc = "bytes per record"});
  s.integer("bits_per_byte", p.bits_per_byte, {.min = 1.0, .max = 64.0, .doc = "bits on the line per byte: start + 8 data + stop"});
  s.number("baud", p.baud, {.unit = "bit/s", .min = 0.0, .above_min = true, .doc = "line rate"});
  // A UART of the time buffered less than a record (an 8250 one character, a
  // 16550 a 16-byte FIFO), so records that cannot be sent at once wait in a
  // driver's buffer: a BSD tty queue holds 256 bytes (TTYHOG) before it gives
  // up on input. Beyond it the oldest waiting record is dropped: the newest
  // pose is the one worth sending.
  p.buffer_records = std::max<int64_t>(1, 256 / p.record_bytes);
  s.integer("buffer_records", p.buffer_records,
            {.min = 1.0, .max = 1e6,
             .doc = "records that may wait for the line behind the one being sent; a newer record arriving at a full "
                    "buffer drops the oldest waiting one",
             .default_doc = "⌊256 / record_bytes⌋ (at least 1): a BSD tty queue of 256 bytes (TTYHOG); a 16550 UART's "
                            "16-byte FIFO holds less than one record"});
  const double record_bits = static_cast<double>(p.record_bytes) * static_cast<double>(p.bits_per_byte);
  s.check_span("baud", 1.0 / p.baud, record_bits, "record_bytes × bits_per_byte (one record)");
  s.modes("host", "poll",
          {{"poll", "the kernel looks every poll_interval_ms; the newest complete record wins",
            [&p](Section& m) {
              p.host_mode = tracker::SerialLinkParams::Poll;
              m.duration("poll_interval_ms", p.poll_interval,
                         {.unit = "ms", .min = 0.0, .above_min = true, .doc = "the Unix hosts of the time polled every 30 ms"});
              clock(m, "poll_", p.poll_clock, "kernel's poll timer");
            }},
           {"interrupt", "an interrupt per received character: no poll wait",
            [&p](Section& m) {
              p.host_mode = tracker::SerialLinkParams::Interrupt;
              m.duration("per_char_interrupt_us", p.per_char_interrupt_cost,
                         {.unit = "us", .doc = "handler cost per character (above the character time, handlers back up)"});
              m.check_span("per_char_interrupt_us", p.per_char_interrupt_cost.to_seconds(),
                           static_cast<double>(p.record_bytes), "record_bytes (one record)");
            }}},
          {.doc = "how the host learns of received characters"});
}

void usb_hid(Section& s, tracker::UsbHidParams& p) {
  s.integer("poll_hz", p.poll_hz,
            {.unit = "Hz", .min = 1.0, .max = 8000.0,
             .doc = "how often the host controller polls the device (bInterval: 125, 250, 500 or 1000 Hz)"});
  clock(s, "poll_", p.poll_clock, "host controller's poll");
  s.duration("os_delay_ms", p.os_delay, {.unit = "ms", .doc = "fixed delay from the transfer to the application"});
  s.duration("os_jitter_ms", p.os_jitter,
             {.unit = "ms", .doc = "random delay added per poll: its bound (uniform) or its mean (exponential)"});
  using Shape = tracker::UsbHidParams::DelayShape;
  s.choice("os_jitter", p.os_jitter_shape, {{"uniform", Shape::Uniform}, {"exponential", Shape::Exponential}},
           {.doc = "shape of the random delay"});
}

}  // namespace

void bind(Section& s, tracker::MotionParams& p) {
  s.doc(
      "Head frame: x right, y up, looking down −z (the OpenGL camera convention). Traces are slerped on the short "
      "arc; sign flips and repeated rows are handled, malformed rows are reported as `file:line: reason`.");
  using Type = tracker::MotionParams::Type;
  s.modes("type", "still",
          {{"still", "a head that does not move",
            [&p](Section& m) {
              p.type = Type::Still;
              start_position(m, p);
              start_orientation(m, p);
            }},
           {"constant", "turning at a constant angular velocity", [&p](Section& m) { p.type = Type::Constant; constant(m, p); }},
           {"sinusoid", "shaking (yaw) and nodding (pitch) sinusoidally", [&p](Section& m) { p.type = Type::Sinusoid; sinusoid(m, p); }},
           {"minimum_jerk", "repeated minimum-jerk turns (10τ³ − 15τ⁴ + 6τ⁵) with rests between",
            [&p](Section& m) { p.type = Type::MinimumJerk; minimum_jerk(m, p); }},
           {"walk", "walking a polyline at constant speed", [&p](Section& m) { p.type = Type::Walk; walk(m, p); }},
           {"trace", "a recorded head motion", [&p](Section& m) { p.type = Type::Trace; trace(m, p); }}},
          {.doc = "which motion"});
}

void bind(Section& s, tracker::TrackerParams& p) {
  s.doc("Samples of the head pose at an exact rate, each ready after an internal delay.");
  s.rate("rate_hz", p.period, {.unit = "Hz", .doc = "sampling rate (exact rational)"});
  clock(s, "", p.clock, "tracker");
  s.duration("internal_delay_ms", p.internal_delay, {.unit = "ms", .doc = "measurement to record ready"});
  s.duration("jitter_ms", p.jitter,
             {.unit = "ms", .doc = "per-sample timing jitter: ±bound (uniform) or standard deviation (normal)"});
  s.choice("jitter", p.jitter_shape, {{"uniform", tracker::TrackerParams::Uniform}, {"normal", tracker::TrackerParams::Normal}},
           {.doc = "shape of the jitter"});
  std::optional<int> present;
  s.optional_object("noise", present, [&p](Section& n, int&) { noise(n, p); }, {.doc = "pose noise (none when absent)"});
  s.optional_object("imu", p.imu, [](Section& i, tracker::ImuChainParams& v) { bind(i, v); },
                    {.doc = "an IMU tracking chain fused by the runtime instead of measured poses (none when absent)"});
}

void bind(Section& s, tracker::TransportParams& p) {
  using Type = tracker::TransportParams::Type;
  s.modes("type", "direct",
          {{"direct", "no delay", [&p](Section&) { p.type = Type::Direct; }},
           {"serial", "records cross an asynchronous serial line",
            [&p](Section& m) {
              p.type = Type::Serial;
              serial(m, p.serial);
            }},
           {"usb_hid", "a USB HID device polled by the host, then handed on by the operating system",
            [&p](Section& m) {
              p.type = Type::UsbHid;
              usb_hid(m, p.usb);
            }}},
          {.doc = "which link"});
}

}  // namespace latsim::sections
