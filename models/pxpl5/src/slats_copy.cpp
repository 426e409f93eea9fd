// Slats: the copy slots of each frame-buffer port, region deadlines, what the
// displayed buffers hold and each field's verdict.
#include <algorithm>

#include "latsim/pxpl5/slats_engine.hpp"

namespace latsim::pxpl5 {

// Both frame buffers receive at once, each its own eye's regions in a fixed
// order (top row, then the rows below). A copy holds the frame buffer's port,
// the sending renderer's port and a ring channel; since every column's renderer
// serves both eyes, the right eye's port queues one slot behind the left's, and
// the 11-slot schedule of SPEC.md section 5 comes out of that contention.
des::Process SlatsEngine::copy_process(int e) {
  const std::string port = unit_name("FB", e);
  for (int64_t i = 0;; ++i) {
    while (fields_dropped_ + static_cast<int64_t>(fields_.size()) <= i) co_await field_started_;
    copy_position_[static_cast<std::size_t>(e)] = i;
    FieldWork& w = *fields_[static_cast<std::size_t>(i - fields_dropped_)];
    for (const int index : copy_order_[static_cast<std::size_t>(e)]) {
      const FieldRegion& reg = regions_[static_cast<std::size_t>(index)];
      co_await *w.rendered[static_cast<std::size_t>(reg.renderer)];
      co_await fb_ports_[static_cast<std::size_t>(e)]->acquire();
      co_await renderer_ports_[static_cast<std::size_t>(reg.renderer)]->acquire();
      const CopyKind kind = choose_copy(w, index, sim_.now() + p_.hw.copy_time_per_region);
      int channel = -1;
      const des::Time start = sim_.now();
      if (kind != CopyKind::none) {
        co_await ring_.acquire();
        channel = ring_.claim();
        co_await sim_.delay(p_.hw.copy_time_per_region);
        ring_.release(channel);
      }
      renderer_ports_[static_cast<std::size_t>(reg.renderer)]->release();
      fb_ports_[static_cast<std::size_t>(e)]->release();
      copied(w, index, kind, start, sim_.now(), channel);
      region_done(w, index);
    }
  }
}

// Top regions (and, without the COPY optimisation, every region) go to the
// buffer swapped in at the retrace, so they are due then; with the
// optimisation lower regions are written straight into the displayed buffer
// and are due when the beam reaches their first line.
des::Time SlatsEngine::deadline(const FieldWork& w, const FieldRegion& r) const {
  if (!writes_displayed_buffer(r)) return timing_.retrace(w.field);
  return timing_.line_time(w.field, r.row * grid_.region_px);
}

// A copy that cannot end before its deadline is late. A late region for the
// buffer swapped in at the retrace is not sent (it could no longer be shown);
// a late lower region is still written, ahead of what remains of the beam.
// With backup_field a late region gets the backup of the last complete field
// instead, unless the buffer already shows exactly that there.
SlatsEngine::CopyKind SlatsEngine::choose_copy(const FieldWork& w, int index, des::Time end_if_started) const {
  const FieldRegion& reg = regions_[static_cast<std::size_t>(index)];
  if (end_if_started < deadline(w, reg)) return CopyKind::data;
  if (p_.backup_field) {
    const int par = parity(w.field);
    const Backup& b = backup_[static_cast<std::size_t>(reg.eye)][static_cast<std::size_t>(par)];
    if (b.field >= 0) {
      const int64_t shown = shown_field_[static_cast<std::size_t>(reg.eye)][static_cast<std::size_t>(par)]
                                        [static_cast<std::size_t>(region_in_eye(index))];
      return shown == b.field ? CopyKind::none : CopyKind::backup;
    }
  }
  return writes_displayed_buffer(reg) ? CopyKind::data : CopyKind::none;
}

void SlatsEngine::copied(FieldWork& w, int index, CopyKind kind, des::Time start, des::Time end, int channel) {
  const FieldRegion& reg = regions_[static_cast<std::size_t>(index)];
  const des::Time due = deadline(w, reg);
  // A region not sent is measured by when it would have arrived.
  const des::Time arrival = kind == CopyKind::none ? start + p_.hw.copy_time_per_region : end;
  w.slack = std::min(w.slack, due - arrival);
  const bool on_time = kind == CopyKind::data && end < due;
  if (on_time) ++w.eye_on_time[static_cast<std::size_t>(reg.eye)];
  else ++w.late;
  if (kind == CopyKind::none) return;

  const char* what = kind == CopyKind::backup ? "BACKUP" : "COPY";
  stage(what, w.field, reg.eye, unit_name("FB", reg.eye), start, end);
  stage(what, w.field, reg.eye, unit_name("R", reg.renderer), start, end);
  stage(what, w.field, reg.eye, unit_name("ring", channel), start, end);
  if (kind == CopyKind::backup) {
    ++counts_.backup_copies;
    const Backup& b = backup_[static_cast<std::size_t>(reg.eye)][static_cast<std::size_t>(parity(w.field))];
    write_region(w.field, index, b.field, b.image);
    return;
  }
  w.copy_start = std::min(w.copy_start, start);
  des::Time& eye_end = w.eye_copy_end[static_cast<std::size_t>(reg.eye)];
  eye_end = std::max(eye_end, end);
  // A late region for the swapped buffer never reaches the displayed one.
  if (!on_time && !writes_displayed_buffer(reg)) return;
  EyeImage image = eye_image(w, reg.eye);
  image.copy_end = end;
  if (timing_.interlaced() || writes_displayed_buffer(reg) || end >= timing_.retrace(w.field)) {
    // Interlaced, this field's rows are not lit before its retrace: writing
    // them now is what the swap at the retrace shows.
    write_region(w.field, index, w.field, image);
    return;
  }
  // Progressive: every field lights the same rows, so the region waits for the swap.
  const int64_t field = w.field;
  sim_.at(timing_.retrace(field), kind_swap_, [this, field, index, image] { write_region(field, index, field, image); });
}

void SlatsEngine::write_region(int64_t field, int index, int64_t image_field, const EyeImage& image) {
  const FieldRegion& reg = regions_[static_cast<std::size_t>(index)];
  shown_field_[static_cast<std::size_t>(reg.eye)][static_cast<std::size_t>(parity(field))]
              [static_cast<std::size_t>(region_in_eye(index))] = image_field;
  if (hooks_.region_written)
    hooks_.region_written(RegionWrite{reg.eye, field, reg.row, reg.column, image_field, image});
}

void SlatsEngine::region_done(FieldWork& w, int index) {
  const FieldRegion& reg = regions_[static_cast<std::size_t>(index)];
  if (--w.regions_held[static_cast<std::size_t>(reg.renderer)] == 0)
    renderer_free_[static_cast<std::size_t>(reg.renderer)]->trigger();
  if (--w.regions_open == 0) verdict(w);
}

EyeImage SlatsEngine::eye_image(const FieldWork& w, int eye) const {
  return EyeImage{eye, w.sample_token, w.transform_start, w.transform_start,
                  w.eye_copy_end[static_cast<std::size_t>(eye)]};
}

// Every region is copied or given up: the field is complete when each arrived
// by its deadline, otherwise missed (torn when some of its own regions show).
void SlatsEngine::verdict(FieldWork& w) {
  const double field_ms = timing_.period_ms();
  int on_time = 0;
  for (int e = 0; e < p_.eyes(); ++e) {
    on_time += w.eye_on_time[static_cast<std::size_t>(e)];
    // The field's own image is on screen from its retrace wherever it arrived in time.
    if (w.eye_on_time[static_cast<std::size_t>(e)] > 0)
      sample("transform_to_retrace_fields", (timing_.retrace(w.field) - w.transform_start).to_ms() / field_ms);
    if (w.eye_copy_end[static_cast<std::size_t>(e)] > des::Time::zero())
      sample("transform_to_copy_end_fields",
             (w.eye_copy_end[static_cast<std::size_t>(e)] - w.transform_start).to_ms() / field_ms);
  }
  if (w.late == 0) {
    ++counts_.complete;
    for (int e = 0; e < p_.eyes(); ++e)
      backup_[static_cast<std::size_t>(e)][static_cast<std::size_t>(parity(w.field))] = Backup{w.field, eye_image(w, e)};
  } else {
    ++counts_.missed;
    if (on_time > 0) ++counts_.torn;
  }
  sample("deadline_slack_ms", w.slack.to_ms());
  if (w.render_start < des::Time::max()) sample("stage_ms.RENDER", (w.render_end - w.transform_start).to_ms());
  if (w.copy_start < des::Time::max()) {
    des::Time last = w.copy_start;
    for (des::Time t : w.eye_copy_end) last = std::max(last, t);
    sample("stage_ms.COPY", (last - w.copy_start).to_ms());
    sample("copy_ms_per_frame", (last - w.copy_start).to_ms());
  }
}

}  // namespace latsim::pxpl5
