#include "frame_stages/pacing_runtime_bind.hpp"

namespace latsim::pipelines::frame_stages {

namespace {

using scenario::Section;

void bind(Section& s, ThrottleParams& t, const char* what) {
  s.integer("late_window", t.window, {.min = 1.0, .max = 1000.0, .doc = "frames looked back at for late ones"});
  s.integer("late_frames", t.late_threshold,
            {.min = 1.0, .max = 1000.0, .doc = "late frames among them that raise the throttle level"});
  s.integer("early_frames", t.early_frames,
            {.min = 1.0, .max = 100000.0,
             .doc = std::string_view(what)});
}

void bind(Section& s, SteamVrParams& p) {
  s.duration("running_start_ms", p.running_start,
             {.unit = "ms", .min = 0.0, .max = 1e3,
              .doc = "WaitGetPoses returns this long before a retrace (Valve, GDC 2015: about 3 ms)"});
  s.choice("reprojection", p.reprojection,
           {{"off", SteamVrParams::Reprojection::off},
            {"interleaved", SteamVrParams::Reprojection::interleaved},
            {"motion_smoothing", SteamVrParams::Reprojection::motion_smoothing}},
           {.doc = "when the application cannot hold the rate: off: no throttling (late frames are re-projected as "
                   "they come); interleaved: half rate, every other refresh re-projected; motion_smoothing: 1/2, 1/3 "
                   "or 1/4 of the rate, the other refreshes synthesised"});
  bind(s, p.throttle, "frames in a row that would have made the level below, to lower it");
}

void bind(Section& s, OculusParams& p) {
  s.number("percentile", p.percentile, {.min = 0.0, .max = 100.0, .doc = "Phase Sync: of the last `window` frame times"});
  s.integer("window", p.window, {.min = 1.0, .max = 100000.0, .doc = "Phase Sync: frame times remembered"});
  s.duration("margin_ms", p.margin, {.unit = "ms", .min = 0.0, .doc = "Phase Sync: added to the percentile"});
  s.flag("asw", p.asw, {.doc = "Asynchronous Spacewarp: half rate with synthesised refreshes when frames are late"});
  bind(s, p.throttle, "frames in a row that would fit a full-rate refresh, to leave half rate");
}

}  // namespace

void bind_runtime_pacing(Section& s, PacingSpec& p) {
  s.object("steamvr", p.steamvr, [](Section& e, SteamVrParams& v) { bind(e, v); }, {.doc = "application: steamvr"});
  s.object("oculus", p.oculus, [](Section& e, OculusParams& v) { bind(e, v); }, {.doc = "application: oculus"});
}

}  // namespace latsim::pipelines::frame_stages
