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
#include "latsim/measurement/panel_rise.hpp"
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
  std::optional<double> display_threshold_deg; ///< the display's threshold (absent: threshold_deg)
  /// Both readings within this of themselves for `rest`: at rest (absent: a
  /// tenth of the smaller threshold). A noisy tracking chain needs more.
  std::optional<double> rest_tolerance_deg;
  des::Time rest = des::Time::ms(100);         ///< both readings steady this long: at rest again
  des::Time max_shift = des::Time::ms(200);    ///< trajectory shifts searched: [−max_shift, max_shift]
  /// A rolling shutter (a phone camera) exposes its rows one after another
  /// over `readout`: a row at fraction y of the frame opens y * readout
  /// after the frame's first row. Global: every row at once.
  enum class Shutter { global, rolling };
  Shutter shutter = Shutter::global;
  des::Time readout;
  double object_row = 0.5;   ///< where the object is in the camera's frame (0: top row)
  double display_row = 0.5;  ///< where the display point is
  /// What the display point shows: the drawn angle, or the flag an
  /// application lights when the drawn object moved more than a threshold
  /// since the previous refresh (the community rig's test zone, read as 0 or
  /// 1, seen at 0.5 through the panel's transition).
  enum class DisplaySignalKind { angle, motion_flag };
  DisplaySignalKind display_signal = DisplaySignalKind::angle;
  /// motion_flag: the application's threshold (absent: calibrated as the
  /// application does, `calibration_factor` times the largest change at rest
  /// over the first `calibration` of the run).
  std::optional<double> flag_threshold_deg;
  double calibration_factor = 1.1;
  des::Time calibration = des::Time::ms(500);
  /// motion_flag: the application decides from poses this many refreshes
  /// older than the ones it draws (an update that reads the tracking data of
  /// the frame before: VRChat's Update, the community rig's application).
  int flag_frames_behind = 0;
  /// The row offsets of the object and the display point: zero for a global shutter.
  des::Time object_offset() const;
  des::Time display_offset() const;
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
  des::Time written;      ///< when the pixel took this value (its transition starts there)
  double from_deg = 0.0;  ///< the value it came from
};

/// The display's pixel: the mean of the angles lit during the exposure,
/// weighted by how long each is lit in it; impulses (zero length) inside the
/// exposure count equally when nothing lit has length there. While a
/// pixel's transition lasts (PanelRise) it shows from_deg + (angle_deg -
/// from_deg) times the transition's fraction: a slow rise is seen late.
class DisplaySignal final : public FilmedSignal {
 public:
  /// `lit` in order of `on`, intervals not overlapping.
  explicit DisplaySignal(std::vector<LitAngle> lit, PanelRise rise = {}) : lit_(std::move(lit)), rise_(rise) {}
  std::optional<double> seen(des::Time open, des::Time close) const override;

 private:
  /// The mean angle shown over [from, to] of one lit interval.
  double mean_over(const LitAngle& l, double angle, double from_angle, des::Time from, des::Time to) const;

  std::vector<LitAngle> lit_;
  PanelRise rise_;
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
/// With a rolling shutter each signal is exposed from its own row's opening
/// (params.object_offset(), display_offset() after the frame's).
RigResult film(const FilmedSignal& object, const FilmedSignal& display, const des::PeriodicSchedule& camera,
               des::Time exposure, des::Time end, const CameraRigParams& params);

/// The display's lit intervals from a shown trace: the angle of each shown
/// orientation about `axis` from `reference` (unwrapped from one to the next).
std::vector<LitAngle> lit_angles(std::span<const ShownSample> shown, const glm::dquat& reference,
                                 const glm::dvec3& axis);

/// The application's motion flag: lit interval i shows 1 when the angle of
/// interval i - behind differs from that of i - behind - 1 by more than
/// `threshold_deg`, else 0 (from_deg: the previous interval's flag, so that
/// the panel's transition between them is seen).
std::vector<LitAngle> motion_flags(std::span<const LitAngle> lit, double threshold_deg, int behind = 0);

/// The threshold an application calibrates at rest: `factor` times the
/// largest change between consecutive lit intervals that begin before `until`.
double calibrated_flag_threshold(std::span<const LitAngle> lit, des::Time until, double factor);

}  // namespace latsim::measurement
