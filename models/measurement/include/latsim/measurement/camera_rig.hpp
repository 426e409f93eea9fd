// A simulated latency-measurement rig: a high-speed camera films the real
// object and a point of the display, and latency is estimated from the film
// as published rigs do it.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "latsim/des/clock.hpp"
#include "latsim/des/time.hpp"
#include "latsim/measurement/shown_trace.hpp"

namespace latsim::measurement {

/// Settings of the rig (/measurement).
struct CameraRigParams {
  /// What is filmed beside the display: the head or the tracked controller.
  enum class Object { head, controller };
  Object object = Object::head;
  des::RationalSeconds frame_period = des::RationalSeconds::period_of_hz(240);  ///< the camera's frame rate
  des::ClockSettings clock;                    ///< camera phase (drawn per replication when absent) and rate error
  std::optional<des::Time> exposure;           ///< shutter open per frame; absent: the whole frame period
  ScreenPoint display_point;                   ///< the pixel filmed
  glm::dvec3 axis{0.0, 1.0, 0.0};              ///< angles are read about this world axis (unit length)
  double threshold_deg = 0.5;                  ///< movement seen once a reading leaves its rest value by more
  des::Time rest = des::Time::ms(100);         ///< both readings steady this long: at rest again
  des::Time max_shift = des::Time::ms(200);    ///< trajectory shifts searched: [−max_shift, max_shift]
};

/// What the camera sees of one object: its mean angle (degrees) over an
/// exposure, or nothing when it is not lit during the exposure.
class FilmedSignal {
 public:
  virtual ~FilmedSignal() = default;
  virtual std::optional<double> seen(des::Time open, des::Time close) const = 0;
};

/// An object always visible: its angle is averaged over 8 evenly spaced
/// instants of the exposure (the midpoint rule), or read at `open` for a
/// zero exposure. Angles are unwrapped within an exposure.
class ObjectSignal final : public FilmedSignal {
 public:
  explicit ObjectSignal(std::function<double(des::Time)> angle_deg) : angle_deg_(std::move(angle_deg)) {}
  std::optional<double> seen(des::Time open, des::Time close) const override;

 private:
  std::function<double(des::Time)> angle_deg_;
};

/// One lit interval of the filmed pixel and the angle it shows.
struct LitAngle {
  des::Time on;
  des::Time off;  ///< == on for an impulse
  double angle_deg;
};

/// The display's pixel: the mean of the angles lit during the exposure,
/// weighted by how long each is lit in it; impulses (zero length) inside the
/// exposure count equally when nothing lit has length there.
class DisplaySignal final : public FilmedSignal {
 public:
  /// `lit` in order of `on`, intervals not overlapping.
  explicit DisplaySignal(std::vector<LitAngle> lit) : lit_(std::move(lit)) {}
  std::optional<double> seen(des::Time open, des::Time close) const override;

 private:
  std::vector<LitAngle> lit_;
};

/// The rig's estimates, one per movement it saw from rest to rest.
struct RigResult {
  std::vector<double> frame_counting_ms;  ///< (display frame − object frame) × frame period
  std::vector<double> shift_ms;           ///< least-squares shift of the display readings onto the object's
  double resolution_ms = 0.0;             ///< half a camera frame: each frame-counted instant's uncertainty
  int64_t frames = 0;                     ///< camera frames filmed
};

/// Films both signals at the camera's frames `camera.at(k)` (k ≥ 0) whose
/// exposure ends by `end`, and estimates latency per movement. A movement
/// starts in the first frame whose object reading differs from its rest value
/// by more than the threshold; the display's start is the first frame from
/// then on whose display reading differs from its rest value by more than
/// the threshold; the movement ends once both readings have stayed within a
/// tenth of the threshold for `rest`, and only then is the next rest value
/// taken (the rig first waits for rest). The shift is the s minimising
/// Σ (display_k − object(t_k − s))² over the movement's frames from
/// max_shift before its start to its end that caught the display lit, the
/// object read between frames by linear interpolation: a 2 ms-or-quarter-frame grid, a finer grid, then a
/// parabola's vertex.
RigResult film(const FilmedSignal& object, const FilmedSignal& display, const des::PeriodicSchedule& camera,
               des::Time exposure, des::Time end, const CameraRigParams& params);

/// The display's lit intervals from a shown trace: the angle of each shown
/// orientation about `axis` from `reference` (unwrapped from one to the next).
std::vector<LitAngle> lit_angles(std::span<const ShownSample> shown, const glm::dquat& reference,
                                 const glm::dvec3& axis);

}  // namespace latsim::measurement
