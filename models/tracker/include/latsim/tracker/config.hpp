// Building tracker-area models from a scenario's JSON objects.
#pragma once

#include <memory>

#include "latsim/scenario/config.hpp"
#include "latsim/tracker/motion_source.hpp"
#include "latsim/tracker/tracker.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::tracker {

/// The scenario's "motion" object. Every type accepts the starting pose
/// "position_m": [0,0,0], "yaw_deg": 0, "pitch_deg": 0 (not read by "walk"
/// and "trace", whose paths set the position; walk reads the angles only
/// when "face_direction" is false). Types and their keys (defaults shown):
///   {"type": "still"}
///   {"type": "constant", "axis": [0,1,0], "rate_deg_s": 100}
///   {"type": "sinusoid", "yaw_amplitude_deg": 30, "yaw_frequency_hz": 0.5,
///    "yaw_phase_deg": 0, "pitch_amplitude_deg": 0, "pitch_frequency_hz": 0.5,
///    "pitch_phase_deg": 0}
///   {"type": "walk", "points": [[x,y,z],...] (required), "speed_m_s": 1.0,
///    "loop": false, "face_direction": true}
///   {"type": "trace", "file": "data/user1_quaternion.txt" (required, relative
///    to the scenario file), "offset_s": 0, "loop": true}
std::unique_ptr<MotionSource> make_motion(const scenario::ConfigNode& node);

/// The scenario's "tracker" object: {"rate_hz": 60 (or exact "60000/1001"),
/// "internal_delay_ms": 0, "jitter_ms": 0, "jitter": "uniform"|"normal",
/// "phase_ms": 0, "noise": {"position_stddev_m": 0, "orientation_stddev_deg": 0}
/// or "noise": {"covariance": 6x6 rows (m^2, then rad^2)}}.
TrackerParams parse_tracker(const scenario::ConfigNode& node);

/// The scenario's "transport" object: {"type": "direct"} or {"type": "serial",
/// "record_bytes": 32, "baud": 19200, "bits_per_byte": 10, "host": "poll",
/// "poll_interval_ms": 30, "poll_phase_ms": 0} or {..., "host": "interrupt",
/// "per_char_interrupt_us": 0}.
std::unique_ptr<Transport> make_transport(const scenario::ConfigNode& node);

}  // namespace latsim::tracker
