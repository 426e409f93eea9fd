#include "latsim/display/display.hpp"

#include <algorithm>
#include <stdexcept>

namespace latsim::display {

namespace {
// Retraces run after other events at the same instant, so a frame that
// completes exactly at a retrace is swapped in by it.
constexpr des::Priority kRetracePriority = 10;
// Pixel scanout runs after the other events of its instant (swaps, arrivals),
// so that both pixel paths agree on what a pixel lit at that instant shows.
constexpr des::Priority kPixelPriority = 5;
}  // namespace

Display::Display(des::Simulator& sim, RasterTiming timing, int eyes, ScanoutFidelity fidelity, int pixel_stride,
                 bool pixel_events)
    : sim_(sim),
      timing_(timing),
      fidelity_(fidelity),
      pixel_stride_(pixel_stride),
      pixel_events_(pixel_events),
      front_(static_cast<size_t>(eyes), -1),
      pending_(static_cast<size_t>(eyes), -1),
      written_(static_cast<size_t>(eyes)) {
  if (eyes < 1 || eyes > 2) throw std::invalid_argument("a display has one or two eyes");
  if (pixel_stride < 1) throw std::invalid_argument("pixel stride must be at least 1");
  kind_retrace_ = sim_.kind("display.retrace");
  if (fidelity_ == ScanoutFidelity::Line) kind_line_ = sim_.kind("display.line");
  if (fidelity_ == ScanoutFidelity::Pixel) kind_pixel_ = sim_.kind(pixel_events_ ? "display.pixel" : "display.pixels");
  const int64_t ppl = timing_.pixels_per_line();
  line_pace_ = stats::TickStepper(timing_.photon_run(0, 0, 0, ppl, 1));
  unit_pace_ = stats::TickStepper(timing_.photon_run(0, 0, 0, pixel_stride_, 1));
  unit_step_ = static_cast<stats::i128>(pixel_stride_) * timing_.ticks_per_slot_num();
  line_step_ = static_cast<stats::i128>(ppl) * timing_.ticks_per_slot_num();
  // What every line's span has in common (emit_line() writes the rest): all
  // columns, no persistence, one sample at the pace of lines.
  const stats::TickRun line = line_pace_.run_from_here(line_step_, 1);
  line_span_ = ScanoutSpan(0, 0, 1, 0, 0, timing_.params().width_px, pixel_stride_, des::Time::zero(), line, line);
}

void Display::present_now(int eye, int64_t image_id) {
  if (batches_pixels()) split_scanout();
  front_.at(eye) = image_id;
  written_.at(eye).clear();
}

void Display::write_region_now(int eye, const BufferRegion& region, int64_t image_id) {
  if (region.x_begin >= region.x_end || region.row_begin >= region.row_end || region.row_step < 1)
    throw std::invalid_argument("an empty frame-buffer region");
  if (batches_pixels()) split_scanout();
  for (WrittenRegion& w : written_.at(eye)) {
    if (w.region == region) {
      w.image_id = image_id;
      return;
    }
    const BufferRegion& o = w.region;
    const bool columns_meet = region.x_begin < o.x_end && o.x_begin < region.x_end;
    bool rows_meet = false;
    for (int row = region.row_begin; row < region.row_end && !rows_meet; row += region.row_step)
      rows_meet = o.contains_row(row);
    if (columns_meet && rows_meet) throw std::invalid_argument("frame-buffer regions overlap");
  }
  // Kept in column order, so that the regions a line crosses come left to right.
  auto& written = written_[static_cast<size_t>(eye)];
  const auto at = std::upper_bound(written.begin(), written.end(), region.x_begin,
                                   [](int x, const WrittenRegion& w) { return x < w.region.x_begin; });
  written.insert(at, WrittenRegion{region, image_id});
}

void Display::present_at_next_retrace(int eye, int64_t image_id) { pending_.at(eye) = image_id; }

void Display::on_retrace(std::function<void(int64_t, des::Time)> fn) { retrace_fns_.push_back(std::move(fn)); }

void Display::add_listener(ScanoutListener* listener) { listeners_.push_back(listener); }

void Display::set_persistence(PersistenceParams params) { persistence_ = Persistence(params, timing_); }

void Display::start(des::Time end) {
  end_ = end;
  const int64_t first = timing_.field_at_or_after(sim_.now());
  if (timing_.field_start(first) < end_)
    sim_.at(timing_.field_start(first), kind_retrace_, [this, first] { retrace(first); }, kRetracePriority);
}

void Display::retrace(int64_t field) {
  for (size_t eye = 0; eye < front_.size(); ++eye) {
    if (pending_[eye] >= 0) {
      front_[eye] = pending_[eye];
      pending_[eye] = -1;
      written_[eye].clear();
    }
  }
  ++fields_shown_;
  const des::Time now = sim_.now();
  for (auto& fn : retrace_fns_) fn(field, now);
  for (auto* l : listeners_)
    for (int eye = 0; eye < eyes(); ++eye) l->on_field_start(eye, field, now);

  const int lines = timing_.lines_per_field();
  const int width = timing_.params().width_px;
  // The field's first line, and its last sample, in exact steppers.
  line_start_ = stats::TickStepper(timing_.photon_run(field, 0, 0, timing_.pixels_per_line(), 1)).at_pace_of(line_pace_);
  switch (fidelity_) {
    case ScanoutFidelity::Field:
      // The whole field is computed now from the content at the retrace:
      // cheap, but a swap during scanout (tearing) is not seen. Lines lit
      // after the end of the run are left out, as the other levels leave them.
      {
        const stats::TickRun run = line_start_.run_from_here(line_step_, static_cast<uint64_t>(lines));
        const uint64_t lit = run.first_index_at_or_above(end_.ticks() + 1);
        if (lit > 0) emit(field, 0, static_cast<int>(lit), 0, width, run.slice(0, lit));
      }
      break;
    case ScanoutFidelity::Line:
      sim_.at(line_start_.time(), kind_line_, [this, field] { scan_line(field, 0); });
      break;
    case ScanoutFidelity::Pixel:
      if (pixel_events_) {
        pixel_ = line_start_.at_pace_of(unit_pace_);
        sim_.at(pixel_.time(), kind_pixel_, [this, field] { scan_pixel(field, 0, 0); }, kPixelPriority);
      } else {
        const int last_x = (units_per_line() - 1) * pixel_stride_;
        line_last_ = stats::TickStepper(timing_.photon_run(field, 0, last_x, timing_.pixels_per_line(), 1))
                         .at_pace_of(line_pace_);
        open_line(field, 0);
      }
      break;
  }

  const int64_t next = field + 1;
  if (timing_.field_start(next) < end_)
    sim_.at(timing_.field_start(next), kind_retrace_, [this, next] { retrace(next); }, kRetracePriority);
}

void Display::scan_line(int64_t field, int line) {
  // The line's instant with the pace of lines, so that a listener can tell
  // that the next line continues it (line_start_ is at now).
  emit_line(field, line);
  const int next = line + 1;
  if (next >= timing_.lines_per_field()) return;
  line_start_.step();
  sim_.at(line_start_.time(), kind_line_, [this, field, next] { scan_line(field, next); });
}

void Display::scan_pixel(int64_t field, int line, int unit) {
  const int width = timing_.params().width_px;
  const int x = unit * pixel_stride_;
  const stats::TickRun photon = stats::TickRun::single(sim_.now().ticks());
  emit(field, line, line + 1, x, std::min(width, x + pixel_stride_), photon);
  int next_unit = unit + 1, next_line = line;
  if (next_unit < units_per_line()) {
    pixel_.step();
  } else {
    next_unit = 0;
    if (++next_line >= timing_.lines_per_field()) return;
    line_start_.step();
    pixel_ = line_start_.at_pace_of(unit_pace_);
  }
  sim_.at(pixel_.time(), kind_pixel_, [this, field, next_line, next_unit] { scan_pixel(field, next_line, next_unit); },
          kPixelPriority);
}

void Display::open_line(int64_t field, int line) {
  open_ = OpenLine{field, line, 0, line_start_.at_pace_of(unit_pace_)};
  // Samples lit at or before the end of the run are scanned, later ones not.
  if (line_start_.time() > end_) {
    open_.line = -1;
    return;
  }
  const des::Time due = std::min(line_last_.time(), end_);
  sim_.at(due, kind_pixel_, [this, field, line] { finish_line(field, line); }, kPixelPriority);
}

void Display::finish_line(int64_t field, int line) {
  // Normally every sample of the line is lit by now; at the end of the run
  // only those at or before it.
  const stats::TickRun rest = open_.at.run_from_here(unit_step_, static_cast<uint64_t>(units_per_line() - open_.next_unit));
  const auto lit = static_cast<int>(rest.first_index_at_or_above(sim_.now().ticks() + 1));
  emit_open(open_.next_unit + lit);
  if (line + 1 >= timing_.lines_per_field() || sim_.now() >= end_) {
    open_.line = -1;
    return;
  }
  line_start_.step();
  line_last_.step();
  open_line(field, line + 1);
}

void Display::split_scanout() {
  if (open_.line < 0) return;
  // Samples lit strictly before now keep what was shown until now.
  const stats::TickRun rest = open_.at.run_from_here(unit_step_, static_cast<uint64_t>(units_per_line() - open_.next_unit));
  const auto lit = static_cast<int>(rest.first_index_at_or_above(sim_.now().ticks()));
  if (lit > 0) emit_open(open_.next_unit + lit);
}

void Display::emit_open(int end_unit) {
  const int n = end_unit - open_.next_unit;
  if (n <= 0) return;
  const int width = timing_.params().width_px;
  const stats::TickRun written = open_.at.run_from_here(unit_step_, static_cast<uint64_t>(n));
  emit(open_.field, open_.line, open_.line + 1, open_.next_unit * pixel_stride_,
       std::min(width, end_unit * pixel_stride_), written);
  if (end_unit < units_per_line()) {
    // Where the next sample is written: one division, only when a line is split.
    open_.at = stats::TickStepper(written.slice(static_cast<uint64_t>(n), 1));
  }
  open_.next_unit = end_unit;
}

void Display::emit(int64_t field, int line, int line_end, int x_begin, int x_end, const stats::TickRun& written) {
  const des::Time written_at = des::Time::ps(written.base);
  const bool persists = persistence_.configured();
  const stats::TickRun photons = persists ? persistence_.photons(field, written) : written;
  ScanoutSpan span(field, line, line_end, timing_.row_of(field, line), x_begin, x_end, pixel_stride_,
                   persists ? persistence_.lit(field, written_at).duration : des::Time::zero(), photons, written);
  emit_span(span);
}

void Display::emit_line(int64_t field, int line) {
  if (persistence_.configured()) {
    emit(field, line, line + 1, 0, timing_.params().width_px, line_start_.run_from_here(line_step_, 1));
    return;
  }
  // Only what changes from line to line is stored (the rest was set at
  // construction), from registers or from state written an event ago, never
  // copied from a TickRun built just now.
  ScanoutSpan& span = line_span_;
  span.field = field;
  span.line = line;
  span.line_end = line + 1;
  span.row = timing_.row_of(field, line);
  span.photon_time = span.written_at = line_start_.time();
  span.photons.base = span.written.base = line_start_.ticks();
  span.photons.offset = span.written.offset = line_start_.remainder();
  emit_span(span);
}

void Display::emit_span(ScanoutSpan& span) {
  for (int eye = 0; eye < eyes(); ++eye) {
    span.eye = eye;
    span.image_id = front_[static_cast<size_t>(eye)];
    if (!written_[static_cast<size_t>(eye)].empty()) {
      emit_samples_by_region(span);
      continue;
    }
    for (auto* l : listeners_) l->on_scanout(span);
  }
}

void Display::emit_samples_by_region(const ScanoutSpan& span) {
  // Regions are rare (a frame buffer filled while it is scanned): the span
  // goes out as the one-sample spans the per-line and per-pixel paths make.
  const bool by_line = span.line_end - span.line > 1;
  for (uint64_t i = 0; i < span.written.count; ++i) {
    ScanoutSpan one = span;
    one.written = span.written.slice(i, 1);
    one.photons = span.photons.slice(i, 1);
    one.written_at = des::Time::ps(one.written.base);
    one.photon_time = des::Time::ps(one.photons.base);
    const int k = static_cast<int>(i);
    if (by_line) {
      one.line = span.line + k;
      one.line_end = one.line + 1;
      one.row = timing_.row_of(span.field, one.line);
    } else if (span.written.count > 1) {
      one.x_begin = span.x_begin + k * pixel_stride_;
      one.x_end = std::min(span.x_end, one.x_begin + pixel_stride_);
    }
    emit_regions(one);
  }
}

void Display::emit_regions(ScanoutSpan span) {
  const int x_end = span.x_end;
  const int64_t front = span.image_id;
  // Neighbouring parts that show the same image go out as one span.
  ScanoutSpan part = span;
  part.x_end = part.x_begin;
  const auto add = [&](int x0, int x1, int64_t id) {
    if (x0 >= x1) return;
    if (part.x_end > part.x_begin && part.image_id != id) {
      for (auto* l : listeners_) l->on_scanout(part);
      part.x_begin = x0;
    }
    part.image_id = id;
    part.x_end = x1;
  };
  int x = span.x_begin;
  for (const WrittenRegion& w : written_[static_cast<size_t>(span.eye)]) {  // in column order
    if (!w.region.contains_row(span.row) || w.region.x_end <= x || w.region.x_begin >= x_end) continue;
    add(x, std::max(x, w.region.x_begin), front);
    x = std::max(x, w.region.x_begin);
    add(x, std::min(x_end, w.region.x_end), w.image_id);
    x = std::max(x, std::min(x_end, w.region.x_end));
  }
  add(x, x_end, front);
  if (part.x_end > part.x_begin)
    for (auto* l : listeners_) l->on_scanout(part);
}

}  // namespace latsim::display
