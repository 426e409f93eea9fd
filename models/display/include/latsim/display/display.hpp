// The HMD's displays: a front buffer per eye, vertical retraces and scanout.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "latsim/des/simulator.hpp"
#include "latsim/display/persistence.hpp"
#include "latsim/display/raster_timing.hpp"

namespace latsim::display {

/// How finely scanout is simulated (and what it costs in events).
enum class ScanoutFidelity {
  Field,  ///< one event per field: content sampled at the retrace, lines computed in a loop
  Line,   ///< one event per active line: content sampled when each line is lit
  Pixel,  ///< one event per (strided) pixel: content sampled when each pixel is lit
};

/// One stretch of scanout that shows one image: a whole line or one pixel.
struct ScanoutSpan {
  int eye = 0;
  int64_t field = 0;
  int line = 0;         ///< line index within the field
  int row = 0;          ///< screen row, 0 = top
  int x_begin = 0;      ///< first pixel column of the span
  int x_end = 0;        ///< one past the last pixel column
  des::Time photon_time;   ///< middle of the lit interval of the span's first pixel
  des::Time written_at;    ///< when scanout wrote the span (the content was read then)
  des::Time lit_duration;  ///< how long each pixel stays lit; 0 without persistence (an impulse)
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
class Display {
 public:
  Display(des::Simulator& sim, RasterTiming timing, int eyes, ScanoutFidelity fidelity, int pixel_stride = 1);

  const RasterTiming& timing() const { return timing_; }
  int eyes() const { return static_cast<int>(front_.size()); }
  ScanoutFidelity fidelity() const { return fidelity_; }

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
  int64_t front(int eye) const { return front_.at(eye); }
  bool has_pending(int eye) const { return pending_.at(eye) >= 0; }

  /// Called at every retrace after pending swaps, before scanout of the field.
  void on_retrace(std::function<void(int64_t field, des::Time retrace)> fn);
  /// Lights written pixels for a while instead of at the scanout instant;
  /// spans then carry the middle of the lit interval as their photon time.
  void set_persistence(PersistenceParams params);
  /// The persistence model (not configured() unless set_persistence was called).
  const Persistence& persistence() const { return persistence_; }
  void add_listener(ScanoutListener* listener);

  /// Schedules retraces (and scanout events) for fields whose retrace lies in [now, end).
  void start(des::Time end);
  int64_t fields_shown() const { return fields_shown_; }

 private:
  void retrace(int64_t field);
  void scan_line(int64_t field, int line);
  void scan_pixel(int64_t field, int line, int x);
  void emit(int eye, int64_t field, int line, int x_begin, int x_end, des::Time t);
  // The parts of [x_begin, x_end) of a row that show written regions, the rest the front image.
  void emit_regions(ScanoutSpan span);

  /// One region written into a displayed buffer and what it shows.
  struct WrittenRegion {
    BufferRegion region;
    int64_t image_id;
  };

  des::Simulator& sim_;
  RasterTiming timing_;
  ScanoutFidelity fidelity_;
  int pixel_stride_;
  std::vector<int64_t> front_;
  std::vector<int64_t> pending_;
  std::vector<std::vector<WrittenRegion>> written_;  // per eye; empty unless regions were written
  std::vector<std::function<void(int64_t, des::Time)>> retrace_fns_;
  std::vector<ScanoutListener*> listeners_;
  Persistence persistence_;
  des::Time end_;
  int64_t fields_shown_ = 0;
  des::KindId kind_retrace_ = 0, kind_line_ = 0, kind_pixel_ = 0;
};

}  // namespace latsim::display
