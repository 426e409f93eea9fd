#include "latsim/tracker/config.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace latsim::tracker {

namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

glm::dvec3 vec3(const scenario::ConfigNode& node, std::string_view key, std::vector<double> def) {
  const std::vector<double> v = node.numbers(key, std::move(def));
  if (v.size() != 3) node.fail(key, "expected 3 numbers [x, y, z], found " + std::to_string(v.size()));
  return glm::dvec3{v[0], v[1], v[2]};
}

glm::dquat start_orientation(const scenario::ConfigNode& node) {
  const double yaw_deg = node.number("yaw_deg", 0.0);
  const double pitch_deg = node.number_in("pitch_deg", 0.0, -90.0, 90.0);
  return quat_from_yaw_pitch(yaw_deg * kRadPerDeg, pitch_deg * kRadPerDeg);
}

Pose start_pose(const scenario::ConfigNode& node) {
  return Pose{vec3(node, "position_m", {0.0, 0.0, 0.0}), start_orientation(node)};
}

std::unique_ptr<MotionSource> make_constant(const scenario::ConfigNode& node) {
  const Pose start = start_pose(node);
  const glm::dvec3 axis = vec3(node, "axis", {0.0, 1.0, 0.0});
  if (axis == glm::dvec3{0.0, 0.0, 0.0}) node.fail("axis", "the rotation axis must not be zero");
  return std::make_unique<ConstantAngularVelocity>(start, axis, node.number("rate_deg_s", 100.0));
}

std::unique_ptr<MotionSource> make_sinusoid(const scenario::ConfigNode& node) {
  SinusoidParams p;
  p.position_m = vec3(node, "position_m", {0.0, 0.0, 0.0});
  p.yaw_amplitude_deg = node.number("yaw_amplitude_deg", 30.0);
  p.yaw_frequency_hz = node.non_negative("yaw_frequency_hz", 0.5);
  p.yaw_phase_deg = node.number("yaw_phase_deg", 0.0);
  p.pitch_amplitude_deg = node.number_in("pitch_amplitude_deg", 0.0, -90.0, 90.0);
  p.pitch_frequency_hz = node.non_negative("pitch_frequency_hz", 0.5);
  p.pitch_phase_deg = node.number("pitch_phase_deg", 0.0);
  return std::make_unique<SinusoidalMotion>(p);
}

std::unique_ptr<MotionSource> make_walk(const scenario::ConfigNode& node) {
  WalkParams p;
  const auto rows = node.number_rows("points");
  if (rows.empty()) node.fail("points", "a walk needs at least one point");
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].size() != 3)
      node.fail("points", "point " + std::to_string(i) + " must have 3 coordinates [x, y, z]");
    p.points_m.emplace_back(rows[i][0], rows[i][1], rows[i][2]);
  }
  p.speed_m_s = node.positive("speed_m_s", 1.0);
  p.loop = node.boolean("loop", false);
  p.face_direction = node.boolean("face_direction", true);
  if (!p.face_direction) p.orientation = start_orientation(node);
  return std::make_unique<PolylineWalk>(std::move(p));
}

std::unique_ptr<MotionSource> make_trace(const scenario::ConfigNode& node) {
  const auto file = node.path("file");
  const des::Time offset = des::Time::from_seconds(node.number_in("offset_s", 0.0, -1e6, 1e6));
  const bool loop = node.boolean("loop", true);
  try {
    return std::make_unique<TraceMotion>(std::make_shared<const Trace>(load_trace(file)), offset, loop);
  } catch (const TraceError& e) {
    node.fail("file", e.what());
  }
}

NoiseCovariance parse_noise(const scenario::ConfigNode& noise) {
  NoiseCovariance c = NoiseCovariance::Zero();
  if (noise.has("covariance")) {
    if (noise.has("position_stddev_m") || noise.has("orientation_stddev_deg"))
      noise.fail("covariance", "give either a covariance or standard deviations, not both");
    const auto rows = noise.number_rows("covariance");
    if (rows.size() != 6) noise.fail("covariance", "expected a 6x6 matrix (x, y, z, rx, ry, rz)");
    for (int i = 0; i < 6; ++i) {
      if (rows[i].size() != 6) noise.fail("covariance", "row " + std::to_string(i) + " must have 6 numbers");
      for (int j = 0; j < 6; ++j) c(i, j) = rows[i][j];
    }
  } else {
    const double position_m = noise.non_negative("position_stddev_m", 0.0);
    const double orientation_rad = noise.non_negative("orientation_stddev_deg", 0.0) * kRadPerDeg;
    for (int i = 0; i < 3; ++i) c(i, i) = position_m * position_m;
    for (int i = 3; i < 6; ++i) c(i, i) = orientation_rad * orientation_rad;
  }
  return c;
}

des::Time positive_duration_ms(const scenario::ConfigNode& node, std::string_view key, double def_ms) {
  const des::Time d = node.duration_ms(key, def_ms);
  if (d <= des::Time::zero()) node.fail(key, "must be greater than zero");
  return d;
}

}  // namespace

std::unique_ptr<MotionSource> make_motion(const scenario::ConfigNode& node) {
  const std::string type = node.choice("type", "still", {"still", "constant", "sinusoid", "walk", "trace"});
  if (type == "constant") return make_constant(node);
  if (type == "sinusoid") return make_sinusoid(node);
  if (type == "walk") return make_walk(node);
  if (type == "trace") return make_trace(node);
  return std::make_unique<StillMotion>(start_pose(node));
}

TrackerParams parse_tracker(const scenario::ConfigNode& node) {
  TrackerParams p;
  p.period = node.rate_as_period("rate_hz", "60");
  p.internal_delay = node.duration_ms("internal_delay_ms", 0.0);
  p.jitter = node.duration_ms("jitter_ms", 0.0);
  p.jitter_shape = node.choice("jitter", "uniform", {"uniform", "normal"}) == "normal" ? TrackerParams::Normal
                                                                                      : TrackerParams::Uniform;
  p.phase = node.duration_ms("phase_ms", 0.0);
  if (const auto noise = node.optional_child("noise")) {
    p.noise_covariance = parse_noise(*noise);
    p.noise_enabled = !p.noise_covariance.isZero(0.0);
    if (p.noise_enabled) {
      try {
        (void)noise_factor(p.noise_covariance);
      } catch (const std::invalid_argument& e) {
        noise->fail("covariance", e.what());
      }
    }
  }
  return p;
}

std::unique_ptr<Transport> make_transport(const scenario::ConfigNode& node) {
  const std::string type = node.choice("type", "direct", {"direct", "serial"});
  if (type == "direct") return std::make_unique<DirectLink>();

  SerialLinkParams p;
  p.record_bytes = node.integer("record_bytes", 32, 1, 1'000'000);
  p.bits_per_byte = node.integer("bits_per_byte", 10, 1, 64);
  p.baud = node.positive("baud", 19200.0);
  const std::string host = node.choice("host", "poll", {"poll", "interrupt"});
  if (host == "poll") {
    p.host_mode = SerialLinkParams::Poll;
    p.poll_interval = positive_duration_ms(node, "poll_interval_ms", 30.0);
    p.poll_phase = node.duration_ms("poll_phase_ms", 0.0);
  } else {
    p.host_mode = SerialLinkParams::Interrupt;
    p.per_char_interrupt_cost = des::Time::from_us(node.non_negative("per_char_interrupt_us", 0.0));
  }
  return std::make_unique<SerialLink>(p);
}

}  // namespace latsim::tracker
