// Rendering Control's swaps of the double buffers and the figures of a
// finished frame (SPEC.md section 4).
#include <algorithm>
#include <string>

#include "latsim/pxpl5/rc_engine.hpp"

namespace latsim::pxpl5 {

const char* RcEngine::eye_label(int eye) const {
  if (!p_.stereo) return "mono";
  return eye == 0 ? "left" : "right";
}

int64_t RcEngine::swap_field_after_now() const {
  int64_t field = timing_.field_after(sim_.now());
  // An interlaced frame starts at an even field (field 0 is the first of frame 0).
  if (p_.swap_at == SwapAt::frame_start && timing_.interlaced() && field % 2 != 0) ++field;
  return field;
}

void RcEngine::swap_eyes(int64_t i, int first, int last) {
  FrameState& f = frame(i);
  FrameReady ready;
  ready.frame = i;
  ready.swap_field = swap_field_after_now();
  ready.swap_at = timing_.retrace(ready.swap_field);
  for (int e = first; e <= last; ++e) {
    EyeState& es = eye(i * p_.eyes() + e);
    es.swap_field = ready.swap_field;
    es.swap_at = ready.swap_at;
    ready.eyes.push_back(EyeImage{e, f.sample_token, f.sample_read_at, es.transform_start, es.copy_end});
  }
  if (!hooks_.frame_ready) return;
  // The display swaps in what it was handed at its next retrace; a swap held
  // back to a frame's start is handed over once the retrace before it has passed.
  if (ready.swap_field == timing_.field_after(sim_.now())) {
    hooks_.frame_ready(ready);
  } else {
    sim_.spawn(present_later(std::move(ready)), sim_.kind("pxpl5.swap"));
  }
}

des::Process RcEngine::present_later(FrameReady ready) {
  const des::Time before = timing_.retrace(ready.swap_field - 1);
  co_await sim_.until(before + des::Time::ps((ready.swap_at - before).ticks() / 2));
  hooks_.frame_ready(ready);
}

void RcEngine::finish_frame(int64_t i) {
  FrameState& f = frame(i);
  const double field_ms = timing_.period_ms();
  f.swap_field = 0;
  for (int e = 0; e < p_.eyes(); ++e) {
    const EyeState& es = eye(i * p_.eyes() + e);
    if (es.swap_field >= f.swap_field) {
      f.swap_field = es.swap_field;
      f.swap_at = es.swap_at;
    }
    // The published analysis' measure: TRANSFORM start to the end of the eye's COPY.
    sample("transform_to_copy_end_fields", (es.copy_end - es.transform_start).to_ms() / field_ms);
    const double to_swap_fields = (es.swap_at - es.transform_start).to_ms() / field_ms;
    sample("transform_to_retrace_fields", to_swap_fields);
    // The same per eye, each over frames: the two eyes of a stereo frame start
    // TRANSFORM an eye apart, so their pool mixes two offsets.
    sample(std::string("transform_to_swap_fields.") + eye_label(e), to_swap_fields);
  }
  sample("copy_ms_per_frame", (sim_.now() - f.copy_start).to_ms());
  // Retrace to retrace between consecutive frames (the last eye's swap): the published "frame time".
  if (i > 0) sample("frame_time_ms", (f.swap_at - frame(i - 1).swap_at).to_ms());
  ++frames_completed_;
}

}  // namespace latsim::pxpl5
