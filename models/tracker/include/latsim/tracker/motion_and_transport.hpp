// Everything the scenario's "motion" and "transport" objects describe, as
// plain structs, and the models built from them.
#pragma once

#include <filesystem>
#include <memory>

#include "latsim/tracker/minimum_jerk.hpp"
#include "latsim/tracker/motion_source.hpp"
#include "latsim/tracker/trace.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::tracker {

/// Which true head motion to simulate, with the settings of every kind.
struct MotionParams {
  enum class Type { Still, Constant, Sinusoid, Walk, Trace, MinimumJerk };
  Type type = Type::Still;
  /// Starting pose of still and constant motion (sinusoid: the position only;
  /// walk: the orientation only, when it does not face its direction).
  glm::dvec3 position_m{0.0, 0.0, 0.0};
  double yaw_deg = 0.0;
  double pitch_deg = 0.0;
  glm::dvec3 axis{0.0, 1.0, 0.0};  ///< constant: rotation axis
  double rate_deg_s = 100.0;       ///< constant: angular speed
  SinusoidParams sinusoid{30.0, 0.5, 0.0, 0.0, 0.5, 0.0, {0.0, 0.0, 0.0}};
  WalkParams walk;
  MinimumJerkParams minimum_jerk;  ///< minimum_jerk: the movements (start pose from position_m, yaw_deg, pitch_deg)
  /// trace: the recording (loaded while the scenario is read), its start offset and looping.
  std::filesystem::path trace_file;
  std::shared_ptr<const Trace> trace;
  des::Time trace_offset;
  bool trace_loop = true;

  /// The starting orientation from yaw_deg and pitch_deg.
  glm::dquat start_orientation() const;
};

std::unique_ptr<MotionSource> make_motion(const MotionParams& params);

/// The link from tracker to host.
struct TransportParams {
  enum class Type { Direct, Serial, UsbHid };
  Type type = Type::Direct;
  SerialLinkParams serial;
  UsbHidParams usb;
};

/// The link; `stream` drives what is random in it (a USB host's delivery delay).
std::unique_ptr<Transport> make_transport(const TransportParams& params,
                                          des::RandomStream stream = des::RandomStream(0, "transport"));

}  // namespace latsim::tracker
