#include "arp/frames.hpp"

#include "latsim/sections/shared.hpp"
#include "latsim/pipelines/pipeline.hpp"

namespace latsim::pipelines {

void bind(scenario::Section& s, FrameOptions& p) {
  s.integer("face_px", p.face_px, {.unit = "px", .min = 1.0, .max = 8192.0, .doc = "cube display memory face size"});
  sections::colour(s, "background", p.background, {.doc = "linear colour [r, g, b] where nothing is drawn"});
  s.numbers("frame_times_s", p.times_s,
            {.unit = "s", .min = 0.0, .max = 1e6, .doc = "write the display memories as images at these times"});
  s.integer("frame_threads", p.threads, {.min = 1.0, .max = 256.0, .doc = "threads rendering those images"});
}

void schedule_frames(RunContext& ctx, const FrameOptions& p, std::function<void()> write) {
  const des::KindId kind = ctx.sim.kind("arp.frame");
  for (double t : p.times_s) {
    const des::Time at = des::Time::from_seconds(t);
    if (at >= des::Time::zero() && at < ctx.duration) ctx.sim.at(at, kind, write, 10);
  }
}

}  // namespace latsim::pipelines
