// The HMD's displays: a front buffer per eye, vertical retraces and scanout.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "latsim/des/simulator.hpp"
#include "latsim/stats/tick_run.hpp"
#include "latsim/display/persistence.hpp"
#include "latsim/display/raster_timing.hpp"

namespace latsim::display {

/// How finely scanout is simulated (and what it costs in events).
enum class ScanoutFidelity {
  Field,  ///< one event per field: content sampled at the retrace, every line at once
  Line,   ///< one event per active line: content sampled when each line is lit
  Pixel,  ///< content sampled when each (strided) pixel is lit
};

/// One stretch of scanout that shows one image: pixels [x_begin, x_end) of
/// the lines [line, line_end) of one field. Latency is sampled in scan order:
/// one sample per line (its first pixel) at field and line fidelity, one per
/// pixel_stride pixels at pixel fidelity; only field fidelity spans several
/// lines, with one sample per line. `written` says when scanout wrote each
/// sample (the content was read then), `photons` the middle of its lit
/// interval (the write time itself without persistence).
struct ScanoutSpan {
  ScanoutSpan() = default;
  /// A span of one eye (eye 0, no image yet) with every other member given;
  /// built member by member, without clearing the whole span first.
  ScanoutSpan(int64_t field_index, int first_line, int end_line, int first_row, int first_x, int end_x, int step_x,
              des::Time lit, const stats::TickRun& photon_run, const stats::TickRun& written_run)
      : field(field_index),
        line(first_line),
        line_end(end_line),
        row(first_row),
        x_begin(first_x),
        x_end(end_x),
        x_step(step_x),
        photon_time(des::Time::ps(photon_run.base)),
        written_at(des::Time::ps(written_run.base)),
        lit_duration(lit),
        photons(photon_run),
        written(written_run) {}

  int eye = 0;
  int64_t field = 0;
  int line = 0;            ///< first line index within the field
  int line_end = 0;        ///< one past the last line
  int row = 0;             ///< screen row of the first line, 0 = top
  int x_begin = 0;         ///< first pixel column of the span (on each line)
  int x_end = 0;           ///< one past the last pixel column
  int x_step = 1;          ///< columns from one sample of a line to the next (pixel fidelity)
  des::Time photon_time;   ///< photons of the first sample
  des::Time written_at;    ///< written of the first sample
  des::Time lit_duration;  ///< how long each pixel stays lit; 0 without persistence (an impulse)
  stats::TickRun photons;    ///< middle of each sample's lit interval
  stats::TickRun written;    ///< when each sample was written
  int64_t image_id = -1;   ///< what the front buffer held; -1 = nothing yet
};

/// A rectangle of one eye's frame buffer: columns [x_begin, x_end) of the
/// screen rows row_begin, row_begin + row_step, ... below row_end (a step of 2
/// picks the rows of one interlaced field).
struct BufferRegion {
  int x_begin = 0;
  int x_end = 0;
  int row_begin = 0;
  int row_end = 0;
  int row_step = 1;

  bool contains_row(int row) const {
    return row >= row_begin && row < row_end && (row - row_begin) % row_step == 0;
  }
  bool operator==(const BufferRegion&) const = default;
};

/// Receives every span the display lights (the latency recorder, frame capture).
class ScanoutListener {
 public:
  virtual ~ScanoutListener() = default;
  virtual void on_field_start(int /*eye*/, int64_t /*field*/, des::Time /*retrace*/) {}
  virtual void on_scanout(const ScanoutSpan& span) = 0;
};

/// Front buffers per eye, swapped at retrace (double buffering) or at once
/// (tearing), scanned out at the chosen fidelity.
///
/// Pixel fidelity costs one event per line: a line is handed to the listeners
/// as spans of pixels once its last pixel is lit, split where what it shows
/// changes mid-line (present_now, split_scanout). With pixel_events it costs
/// one event per pixel (the reference the batched path is tested against).
/// Either way a pixel lit at the very instant of a change shows the change:
/// pixel scanout runs after every other event of that instant except the
/// retrace.
class Display {
 public:
  Display(des::Simulator& sim, RasterTiming timing, int eyes, ScanoutFidelity fidelity, int pixel_stride = 1,
          bool pixel_events = false);

  const RasterTiming& timing() const { return timing_; }
  int eyes() const { return static_cast<int>(front_.size()); }
  ScanoutFidelity fidelity() const { return fidelity_; }
  /// True at pixel fidelity without pixel_events: lines are scanned as batches.
  bool batches_pixels() const { return fidelity_ == ScanoutFidelity::Pixel && !pixel_events_; }

  /// Makes `image_id` visible from now on (no vsync: a swap mid-scan tears).
  void present_now(int eye, int64_t image_id);
  /// Swaps `image_id` in at the next vertical retrace (a later call before
  /// that retrace replaces it: only the newest pending image is shown).
  void present_at_next_retrace(int eye, int64_t image_id);
  /// Writes `image_id` into one region of the eye's displayed buffer now, for
  /// a frame buffer filled region by region while it is scanned out: lines lit
  /// from now on show it there (a line crossing regions of different images
  /// is lit as one span per stretch of one image). Regions of an
  /// eye never overlap unless equal; a whole image presented later replaces them.
  void write_region_now(int eye, const BufferRegion& region, int64_t image_id);
  /// What the listeners will see changes now by other means than a swap (an
  /// address recalculation display reads a newer orientation): pixels lit
  /// before now are handed over first. Only batched pixel scanout needs this.
  void split_scanout();
  int64_t front(int eye) const { return front_.at(eye); }

  /// Called at every retrace after pending swaps, before scanout of the field.
  void on_retrace(std::function<void(int64_t field, des::Time retrace)> fn);
  /// Lights written pixels for a while instead of at the scanout instant;
  /// spans then carry the middle of the lit interval as their photon times.
  void set_persistence(PersistenceParams params);
  /// The persistence model (not configured() unless set_persistence was called).
  const Persistence& persistence() const { return persistence_; }
  void add_listener(ScanoutListener* listener);

  /// Schedules retraces (and scanout events) for fields whose retrace lies in [now, end).
  void start(des::Time end);
  int64_t fields_shown() const { return fields_shown_; }

 private:
  // The line of batched pixel scanout whose pixels are not all handed over yet.
  struct OpenLine {
    int64_t field = -1;
    int line = -1;         // -1: none
    int next_unit = 0;     // first sample (pixel_stride pixels) not handed over
    stats::TickStepper at;   // photon time of next_unit
  };

  void retrace(int64_t field);
  void scan_line(int64_t field, int line);
  void scan_pixel(int64_t field, int line, int unit);
  void open_line(int64_t field, int line);
  void finish_line(int64_t field, int line);
  // Hands over the open line's samples [next_unit, end_unit).
  void emit_open(int end_unit);
  // Hands a span of samples written at `written` to every listener, once per eye.
  void emit(int64_t field, int line, int line_end, int x_begin, int x_end, const stats::TickRun& written);
  // The same for the whole line at line_start_, built in place (line_span_).
  void emit_line(int64_t field, int line);
  // Hands `span` to every listener, once per eye.
  void emit_span(ScanoutSpan& span);
  // An eye with written regions: the span one sample at a time, each split by the regions.
  void emit_samples_by_region(const ScanoutSpan& span);
  // The parts of [x_begin, x_end) of a one-sample span that show written regions, the rest the front image.
  void emit_regions(ScanoutSpan span);
  int units_per_line() const { return (timing_.params().width_px + pixel_stride_ - 1) / pixel_stride_; }

  /// One region written into a displayed buffer and what it shows.
  struct WrittenRegion {
    BufferRegion region;
    int64_t image_id;
  };

  des::Simulator& sim_;
  RasterTiming timing_;
  ScanoutFidelity fidelity_;
  int pixel_stride_;
  bool pixel_events_;
  std::vector<int64_t> front_;
  std::vector<int64_t> pending_;
  std::vector<std::vector<WrittenRegion>> written_;  // per eye; empty unless regions were written
  std::vector<std::function<void(int64_t, des::Time)>> retrace_fns_;
  std::vector<ScanoutListener*> listeners_;
  Persistence persistence_;
  des::Time end_;
  int64_t fields_shown_ = 0;
  des::KindId kind_retrace_ = 0, kind_line_ = 0, kind_pixel_ = 0;
  // Exact steppers (no division per line or pixel): line starts and last
  // samples of the current field, the pixel sample within a line, and the
  // paces of one line and of one sample.
  stats::TickStepper line_start_, line_last_, pixel_;
  stats::TickStepper line_pace_, unit_pace_;
  stats::i128 unit_step_ = 0;  // ticks per sample, times the raster's D
  stats::i128 line_step_ = 0;  // ticks per line, times the raster's D
  OpenLine open_;
  // Line scanout's span, filled in place for each line: copying a just-built
  // 80-byte TickRun costs a failed store-to-load forward on every 16-byte
  // chunk, which was a fifth of a line-level run.
  ScanoutSpan line_span_;
};

}  // namespace latsim::display
