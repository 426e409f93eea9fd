#include "latsim/display/display.hpp"

#include <algorithm>
#include <stdexcept>

namespace latsim::display {

namespace {
// Retraces run after other events at the same instant, so a frame that
// completes exactly at a retrace is swapped in by it.
constexpr des::Priority kRetracePriority = 10;
}  // namespace

Display::Display(des::Simulator& sim, RasterTiming timing, int eyes, ScanoutFidelity fidelity, int pixel_stride)
    : sim_(sim),
      timing_(timing),
      fidelity_(fidelity),
      pixel_stride_(pixel_stride),
      front_(static_cast<size_t>(eyes), -1),
      pending_(static_cast<size_t>(eyes), -1),
      written_(static_cast<size_t>(eyes)) {
  if (eyes < 1 || eyes > 2) throw std::invalid_argument("a display has one or two eyes");
  if (pixel_stride < 1) throw std::invalid_argument("pixel stride must be at least 1");
  kind_retrace_ = sim_.kind("display.retrace");
  if (fidelity_ == ScanoutFidelity::Line) kind_line_ = sim_.kind("display.line");
  if (fidelity_ == ScanoutFidelity::Pixel) kind_pixel_ = sim_.kind("display.pixel");
}

void Display::present_now(int eye, int64_t image_id) {
  front_.at(eye) = image_id;
  written_.at(eye).clear();
}

void Display::write_region_now(int eye, const BufferRegion& region, int64_t image_id) {
  if (region.x_begin >= region.x_end || region.row_begin >= region.row_end || region.row_step < 1)
    throw std::invalid_argument("an empty frame-buffer region");
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

  switch (fidelity_) {
    case ScanoutFidelity::Field:
      // The whole field is computed now from the content at the retrace:
      // cheap, but a swap during scanout (tearing) is not seen. Lines lit
      // after the end of the run are left out, as the other levels leave them.
      for (int j = 0; j < timing_.lines_per_field(); ++j) {
        const des::Time t = timing_.line_time(field, j);
        if (t > end_) break;
        for (int eye = 0; eye < eyes(); ++eye) emit(eye, field, j, 0, timing_.params().width_px, t);
      }
      break;
    case ScanoutFidelity::Line:
      sim_.at(timing_.line_time(field, 0), kind_line_, [this, field] { scan_line(field, 0); });
      break;
    case ScanoutFidelity::Pixel:
      sim_.at(timing_.pixel_time(field, 0, 0), kind_pixel_, [this, field] { scan_pixel(field, 0, 0); });
      break;
  }

  const int64_t next = field + 1;
  if (timing_.field_start(next) < end_)
    sim_.at(timing_.field_start(next), kind_retrace_, [this, next] { retrace(next); }, kRetracePriority);
}

void Display::scan_line(int64_t field, int line) {
  for (int eye = 0; eye < eyes(); ++eye) emit(eye, field, line, 0, timing_.params().width_px, sim_.now());
  const int next = line + 1;
  if (next < timing_.lines_per_field())
    sim_.at(timing_.line_time(field, next), kind_line_, [this, field, next] { scan_line(field, next); });
}

void Display::scan_pixel(int64_t field, int line, int x) {
  const int width = timing_.params().width_px;
  const int x_end = std::min(width, x + pixel_stride_);
  for (int eye = 0; eye < eyes(); ++eye) emit(eye, field, line, x, x_end, sim_.now());
  int nx = x_end, nl = line;
  if (nx >= width) {
    nx = 0;
    ++nl;
  }
  if (nl < timing_.lines_per_field())
    sim_.at(timing_.pixel_time(field, nl, nx), kind_pixel_, [this, field, nl, nx] { scan_pixel(field, nl, nx); });
}

void Display::emit(int eye, int64_t field, int line, int x_begin, int x_end, des::Time t) {
  ScanoutSpan span;
  span.eye = eye;
  span.field = field;
  span.line = line;
  span.row = timing_.row_of(field, line);
  span.x_begin = x_begin;
  span.x_end = x_end;
  span.written_at = t;
  if (persistence_.configured()) {
    const LitInterval lit = persistence_.lit(field, t);
    span.photon_time = lit.middle();
    span.lit_duration = lit.duration;
  } else {
    span.photon_time = t;
  }
  span.image_id = front_[static_cast<size_t>(eye)];
  if (!written_[static_cast<size_t>(eye)].empty()) return emit_regions(span);
  for (auto* l : listeners_) l->on_scanout(span);
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
