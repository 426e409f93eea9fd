// presentmon.csv: a run's application frames in the columns of a PresentMon
// capture, so that the tools that read captures read runs too.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "latsim/des/time.hpp"
#include "latsim/results/frame_times.hpp"
#include "latsim/results/run_files.hpp"

namespace latsim::results {

/// Streams one row per application frame, in frame order, in the current
/// PresentMon column names latsim can fill honestly (docs/figures.md,
/// "presentmon.csv", defines each). A row is written once it is final: the
/// frame is complete and either it was shown and a later frame has been
/// shown (no earlier photon of it can follow), or a later frame was shown
/// first (it never will be: NA in the display columns), or the pipeline shows
/// none of its frames (NA too). Times in
/// milliseconds with nine decimals and seconds with twelve: exact to the
/// picosecond, latsim's unit of time.
class PresentMonLog {
 public:
  PresentMonLog(std::string application, PresentFacts presents)
      : application_(std::move(application)), presents_(std::move(presents)) {}

  /// The column names, in order.
  static const std::vector<std::string>& columns();

  /// Frame `f.frame` is complete (frames may complete out of order).
  void completed(const FrameTimes& f, RunFiles& files);
  /// An image of frame `frame` is first lit at `photon`.
  void shown(int64_t frame, des::Time photon, RunFiles& files);
  /// Frame `frame` began to be scanned out at `t` (MsUntilScanout; the first such instant counts).
  void flipped(int64_t frame, des::Time t);
  /// Writes the rows whose frame was shown or passed over; those after the
  /// last frame shown are still on their way to the display and left out.
  /// Commits the file (nothing when no row was written).
  void finish(RunFiles& files);
  /// Rows written so far.
  int64_t rows() const { return rows_; }

 private:
  struct Pending {
    std::optional<FrameTimes> times;  ///< set once complete
    std::optional<des::Time> photon;  ///< its first photon, once shown
    std::optional<des::Time> flip;    ///< when its scanout began, where the pipeline says
  };
  Pending& pending(int64_t frame);
  void flush(RunFiles& files, int64_t below_frame);
  void write_row(const FrameTimes& f, const Pending& p, RunFiles& files);

  std::string application_;
  PresentFacts presents_;
  std::deque<Pending> pending_;  ///< frames base_, base_ + 1, ...
  int64_t base_ = 0;
  int64_t newest_shown_ = -1;
  std::optional<des::Time> last_present_, last_photon_;
  StreamedFile file_;
  std::string prefix_;  ///< the cells every row begins with
  std::string mode_cell_;  ///< the PresentMode cell, with its comma
  std::string batch_;   ///< rows not yet given to file_ (its capacity is reused)
  int64_t rows_ = 0;
};

}  // namespace latsim::results
