// Bindings of /apparent_latency and /measurement.
#include <cmath>

#include <glm/geometric.hpp>

#include "latsim/sections/shared.hpp"

namespace latsim::sections {

using scenario::Section;

void bind(Section& s, measurement::ApparentLatencyParams& p) {
  s.doc(
      "Apparent latency: the time shift that best aligns the orientation shown at the centre of eye 0's display "
      "with the true head orientation, fitted by least squares over a sliding window of refreshes, split by motion "
      "phase (`/motion_phases`, its defaults when absent) into `apparent_latency_ms_onset`, `_steady` and `_stop`, "
      "with `prediction_catch_up_ms` and, per movement from rest, `apparent_latency_ms_start` (docs/figures.md). "
      "Keeps one sample per refresh while the run lasts.");
  s.duration("window_ms", p.window,
             {.unit = "ms", .min = 0.0, .max = 1e4, .above_min = true, .doc = "length of the sliding window"});
  s.duration("step_ms", p.step,
             {.unit = "ms", .min = 0.0, .max = 1e4, .above_min = true, .doc = "spacing of the window centres"});
  s.duration("max_shift_ms", p.max_shift,
             {.unit = "ms", .min = 0.0, .max = 1e4, .above_min = true, .doc = "shifts searched: ±max_shift_ms"});
  s.number("catch_up_tolerance_ms", p.catch_up_tolerance_ms,
           {.unit = "ms", .min = 0.0, .max = 1e4,
            .doc = "prediction has caught up once a window's shift is at most the steady value plus this"});
  s.number("start_threshold_deg", p.start_threshold_deg,
           {.unit = "deg", .min = 0.0, .max = 180.0, .above_min = true,
            .doc = "apparent_latency_ms_start: a movement has begun, true or shown, once it has turned this far from "
                   "rest"});
}

void bind(Section& s, measurement::CameraRigParams& p, std::string_view head_only) {
  s.doc(
      "A simulated latency-measurement rig: a high-speed camera films the real head (or object) and one point of "
      "eye 0's display, and latency is estimated per movement by frame counting (`measured_latency_ms`) and by the "
      "least-squares shift of the two filmed trajectories (`measured_latency_shift_ms`); "
      "`measurement_resolution_ms` is half a camera frame (docs/figures.md).");
  using Object = measurement::CameraRigParams::Object;
  s.choice("object", p.object, {{"head", Object::head}, {"controller", Object::controller}},
           {.doc = "what the camera films beside the display: the head, or the controller of /controller (drawn at "
                   "the display point)"});
  s.check("object", head_only.empty() || p.object == Object::head, head_only);
  s.rate("fps", p.frame_period, {.unit = "Hz", .doc = "camera frame rate (120, 240, 1000 …)"});
  clock(s, "", p.clock, "camera");
  s.duration("exposure_ms", p.exposure,
             {.unit = "ms", .min = 0.0, .max = 1e4, .doc = "shutter open per frame",
              .default_doc = "the whole frame period"});
  std::vector<double> point{p.display_point.x, p.display_point.y};
  s.numbers("display_point", point,
            {.min = 0.0, .max = 1.0, .count = 2,
             .doc = "the filmed pixel [x, y] as fractions of the width and of a field's lines (0, 0: top left)"});
  if (point.size() == 2) p.display_point = measurement::ScreenPoint{point[0], point[1]};
  vec3(s, "axis", p.axis, {.doc = "angles are read about this world axis ([0, 1, 0]: yaw)"});
  s.check("axis", p.axis != glm::dvec3(0.0), "the axis must not be zero");
  if (p.axis != glm::dvec3(0.0)) p.axis = glm::normalize(p.axis);
  s.number("threshold_deg", p.threshold_deg,
           {.unit = "deg", .min = 0.0, .max = 360.0, .above_min = true,
            .doc = "a reading this far from its rest value shows movement"});
  s.duration("rest_ms", p.rest,
             {.unit = "ms", .min = 0.0, .max = 1e5, .above_min = true,
              .doc = "both readings steady (within rest_tolerance_deg) this long: at rest"});
  s.duration("max_shift_ms", p.max_shift,
             {.unit = "ms", .min = 0.0, .max = 1e4, .above_min = true, .doc = "trajectory shifts searched: ±max_shift_ms"});
  s.number("display_threshold_deg", p.display_threshold_deg,
           {.unit = "deg", .min = 0.0, .max = 360.0, .above_min = true,
            .doc = "the display's reading this far from its rest value shows its movement",
            .default_doc = "threshold_deg"});
  s.number("rest_tolerance_deg", p.rest_tolerance_deg,
           {.unit = "deg", .min = 0.0, .max = 360.0, .above_min = true,
            .doc = "both readings within this of themselves for rest_ms: at rest (a noisy tracking chain jitters)",
            .default_doc = "a tenth of the smaller of threshold_deg and display_threshold_deg"});
  using Shutter = measurement::CameraRigParams::Shutter;
  s.choice("shutter", p.shutter, {{"global", Shutter::global}, {"rolling", Shutter::rolling}},
           {.doc = "global: every row of a camera frame exposed at once; rolling: row by row over readout_ms (a "
                   "phone camera), the object and the display point at their own rows"});
  s.duration("readout_ms", p.readout,
             {.unit = "ms", .min = 0.0, .max = 1e4, .doc = "rolling: from the first row's exposure to the last's"});
  s.number("object_row", p.object_row,
           {.min = 0.0, .max = 1.0, .doc = "rolling: the object's row as a fraction of the frame height (0: top)"});
  s.number("display_row", p.display_row,
           {.min = 0.0, .max = 1.0, .doc = "rolling: the display point's row as a fraction of the frame height"});
  using Kind = measurement::CameraRigParams::DisplaySignalKind;
  s.choice("display_signal", p.display_signal, {{"angle", Kind::angle}, {"motion_flag", Kind::motion_flag}},
           {.doc = "what the display point shows: the drawn angle; or motion_flag, 1 while the drawn object moved more "
                   "than flag_threshold_deg since the previous refresh, else 0, seen as moving past 0.5 (the community "
                   "rig's test zone that turns red; display_threshold_deg is then 0.5)"});
  s.number("flag_threshold_deg", p.flag_threshold_deg,
           {.unit = "deg", .min = 0.0, .max = 360.0,
            .doc = "motion_flag: the application's threshold on the change from one refresh to the next",
            .default_doc = "calibrated: calibration_factor times the largest change over the first calibration_ms"});
  s.number("calibration_factor", p.calibration_factor,
           {.min = 1.0, .max = 100.0, .doc = "motion_flag: the calibrated threshold over the largest change at rest"});
  s.duration("calibration_ms", p.calibration,
             {.unit = "ms", .min = 0.0, .max = 1e6, .above_min = true,
              .doc = "motion_flag: the rest at the start of the run the threshold is calibrated over"});
  s.integer("flag_frames_behind", p.flag_frames_behind,
            {.min = 0.0, .max = 16.0,
             .doc = "motion_flag: the application decides from the poses of this many refreshes before the one it "
                    "draws (VRChat's Update reads the tracking data of the frame before)"});
  if (p.display_signal == Kind::motion_flag) p.display_threshold_deg = p.display_threshold_deg.value_or(0.5);
  if (p.shutter == Shutter::rolling)
    s.check("readout_ms", p.readout.to_seconds() <= p.frame_period.to_seconds(),
            "a rolling shutter reads its rows out within one frame period");
  if (p.exposure)
    s.check("exposure_ms", p.exposure->to_seconds() <= p.frame_period.to_seconds(),
            "the shutter cannot stay open longer than a frame period");
}

}  // namespace latsim::sections
