#include "latsim/tracker/motion_and_transport.hpp"
#include "latsim/units/units.hpp"


namespace latsim::tracker {

glm::dquat MotionParams::start_orientation() const {
  return quat_from_yaw_pitch(yaw_deg * units::kRadPerDeg, pitch_deg * units::kRadPerDeg);
}

std::unique_ptr<MotionSource> make_motion(const MotionParams& p) {
  const Pose start{p.position_m, p.start_orientation()};
  switch (p.type) {
    case MotionParams::Type::Constant:
      return std::make_unique<ConstantAngularVelocity>(start, p.axis, p.rate_deg_s);
    case MotionParams::Type::Sinusoid:
      return std::make_unique<SinusoidalMotion>(p.sinusoid);
    case MotionParams::Type::MinimumJerk: {
      MinimumJerkParams m = p.minimum_jerk;
      m.start = start;
      return std::make_unique<MinimumJerkMotion>(m);
    }
    case MotionParams::Type::Walk:
      return std::make_unique<PolylineWalk>(p.walk);
    case MotionParams::Type::Trace:
      return std::make_unique<TraceMotion>(p.trace ? p.trace : std::make_shared<const Trace>(load_trace(p.trace_file)),
                                           p.trace_offset, p.trace_loop);
    case MotionParams::Type::Still:
      break;
  }
  return std::make_unique<StillMotion>(start);
}

std::unique_ptr<Transport> make_transport(const TransportParams& p, des::RandomStream stream) {
  if (p.type == TransportParams::Type::Serial) return std::make_unique<SerialLink>(p.serial);
  if (p.type == TransportParams::Type::UsbHid) return std::make_unique<UsbHidLink>(p.usb, stream);
  return std::make_unique<DirectLink>();
}

}  // namespace latsim::tracker
