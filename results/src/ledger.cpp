#include "latsim/results/ledger.hpp"

#include <cstdio>
#include <sstream>

#include "latsim/results/run_files.hpp"

namespace latsim::results {

namespace {

// Column order of fields.csv (see field_columns()).
enum FieldColumn { kField, kEye, kImage, kFrame, kSample, kMeasured, kOrientationAtScanout, kOrientationMeasured,
                   kFirstLine, kFirstX, kLastLine, kLastX, kRetrace, kScanoutStart, kFieldColumns };

std::string csv_of_rows(const std::vector<std::string>& columns, const std::vector<std::vector<int64_t>>& rows) {
  std::ostringstream out;
  for (size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
  out << '\n';
  for (const auto& row : rows) {
    for (size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << row[i];
    out << '\n';
  }
  return out.str();
}

}  // namespace

const std::vector<std::string>& Ledger::frame_columns() {
  static const std::vector<std::string> cols{"frame",           "eye",           "field",
                                             "sample",          "measured_ps",   "host_received_ps",
                                             "render_start_ps", "render_end_ps", "predicted_for_ps",
                                             "swap_ps",         "scanout_start_ps", "scanout_end_ps",
                                             "image",           "continues_image"};
  return cols;
}

const std::vector<std::string>& Ledger::field_columns() {
  static const std::vector<std::string> cols{"field",     "eye",         "image",
                                             "frame",     "sample",      "measured_ps",
                                             "orientation_at_scanout",   "orientation_measured_ps",
                                             "first_line", "first_x",    "last_line",
                                             "last_x",    "retrace_ps",  "scanout_start_ps"};
  return cols;
}

const std::vector<std::string>& Ledger::tracker_columns() {
  static const std::vector<std::string> cols{"sample", "measured_ps", "ready_ps", "start_ps", "end_ps", "visible_ps"};
  return cols;
}

void Ledger::image_shown(int64_t image_id, const ImageRecord& img, const display::ScanoutSpan& span,
                         const display::RasterTiming& timing) {
  const des::Time swap = timing.field_start(span.field);
  const des::Time scan_start = timing.scanout_start(span.field);
  const des::Time scan_end = timing.line_time(span.field, timing.lines_per_field() - 1);
  frame_rows_.push_back({img.frame, img.eye, span.field, img.sample.index, img.sample.measured_at.ticks(),
                         img.host_received.ticks(), img.render_start.ticks(), img.render_end.ticks(),
                         img.predicted_for.ticks(), swap.ticks(), scan_start.ticks(), scan_end.ticks(), image_id,
                         img.continues_image ? 1 : 0});
}

// One row per run of consecutive spans of a field and eye that show one image.
void Ledger::span(int64_t image_id, const ImageRecord& img, const display::ScanoutSpan& span,
                  const display::RasterTiming& timing) {
  // The span's last sample: its last line, or the last sample of its one line.
  const bool one_line = span.line_end - span.line == 1;
  const int64_t last_x = one_line ? span.x_begin + static_cast<int64_t>(span.written.count - 1) * span.x_step : 0;
  for (auto it = field_rows_.rbegin(); it != field_rows_.rend() && (*it)[kField] == span.field; ++it) {
    if ((*it)[kEye] != span.eye) continue;
    if ((*it)[kImage] == image_id) {
      (*it)[kLastLine] = span.line_end - 1;
      (*it)[kLastX] = last_x;
      return;
    }
    break;
  }
  std::vector<int64_t> row(kFieldColumns);
  row[kField] = span.field;
  row[kEye] = span.eye;
  row[kImage] = image_id;
  row[kFrame] = img.frame;
  row[kSample] = img.sample.index;
  row[kMeasured] = img.sample.measured_at.ticks();
  row[kOrientationAtScanout] = img.orientation_at_scanout ? 1 : 0;
  // The orientation's sample when the image fixes it (-1: looked up per span).
  row[kOrientationMeasured] = img.orientation_at_scanout               ? -1
                              : img.warp == ImageRecord::Warp::rotation ? img.orientation_measured_at.ticks()
                                                                        : img.sample.measured_at.ticks();
  row[kFirstLine] = span.line;
  row[kLastLine] = span.line_end - 1;
  row[kFirstX] = span.x_begin;
  row[kLastX] = one_line ? last_x : span.x_begin;
  row[kRetrace] = timing.field_start(span.field).ticks();
  row[kScanoutStart] = timing.scanout_start(span.field).ticks();
  field_rows_.push_back(std::move(row));
}

void Ledger::carried(const tracker::TrackerSample& s, const tracker::Carriage& c) {
  tracker_rows_.push_back(
      {s.index, s.measured_at.ticks(), s.ready_at.ticks(), c.start.ticks(), c.end.ticks(), c.visible.ticks()});
}

void Ledger::write(RunFiles& files) const {
  files.write_text("frames.csv", csv_of_rows(frame_columns(), frame_rows_));
  files.write_text("fields.csv", csv_of_rows(field_columns(), field_rows_));
  files.write_text("tracker.csv", csv_of_rows(tracker_columns(), tracker_rows_));
}

void SampleLog::write(RunFiles& files) const {
  std::ostringstream s;
  s << "t_ms,name,value\n";
  char buf[96];
  for (const auto& x : samples_) {
    std::snprintf(buf, sizeof buf, "%.6f,%s,%.9g\n", x.t_ms, x.name.c_str(), x.value);
    s << buf;
  }
  files.write_text("samples.csv", s.str());
}

}  // namespace latsim::results
