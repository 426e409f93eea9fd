// The ledger of a run: frames.csv (one row per image first shown),
// fields.csv (one row per run of spans of a field showing one image) and
// tracker.csv (one row per sample carried); and the sample log, samples.csv
// (every figure's raw samples). Both only when asked for.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "latsim/display/display.hpp"
#include "latsim/display/raster_timing.hpp"
#include "latsim/results/image_record.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::results {

class RunFiles;

class Ledger {
 public:
  void enable(bool on) { on_ = on; }
  bool on() const { return on_; }

  /// An image first shown by `span` (image id `image_id`).
  void image_shown(int64_t image_id, const ImageRecord& img, const display::ScanoutSpan& span,
                   const display::RasterTiming& timing);
  /// A span showing image `image_id`: extends the field's last row of that
  /// eye when it shows the same image, else starts a row.
  void span(int64_t image_id, const ImageRecord& img, const display::ScanoutSpan& span,
            const display::RasterTiming& timing);
  /// A record given to the link.
  void carried(const tracker::TrackerSample& s, const tracker::Carriage& c);

  static const std::vector<std::string>& frame_columns();
  static const std::vector<std::string>& field_columns();
  static const std::vector<std::string>& tracker_columns();
  const std::vector<std::vector<int64_t>>& frames() const { return frame_rows_; }
  const std::vector<std::vector<int64_t>>& fields() const { return field_rows_; }
  const std::vector<std::vector<int64_t>>& tracker() const { return tracker_rows_; }

  /// Writes frames.csv, fields.csv and tracker.csv.
  void write(RunFiles& files) const;

 private:
  bool on_ = false;
  std::vector<std::vector<int64_t>> frame_rows_;
  std::vector<std::vector<int64_t>> field_rows_;
  std::vector<std::vector<int64_t>> tracker_rows_;
};

/// Raw (time, name, value) samples of every figure, for samples.csv.
class SampleLog {
 public:
  struct Sample {
    double t_ms;
    std::string name;
    double value;
  };
  void enable(bool on) { on_ = on; }
  bool on() const { return on_; }
  void add(double t_ms, std::string name, double value) { samples_.push_back({t_ms, std::move(name), value}); }
  const std::vector<Sample>& samples() const { return samples_; }
  /// Writes samples.csv.
  void write(RunFiles& files) const;

 private:
  bool on_ = false;
  std::vector<Sample> samples_;
};

}  // namespace latsim::results
