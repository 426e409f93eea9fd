// The frames of double buffering over a grid of clock phases, tallied exactly
// without visiting every phase point: the newest sample seen at a cutoff is
// one of two for every tracker phase within one period, so each frame costs a
// few divisions per poll phase whatever the number of tracker phases.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "latsim/des/time.hpp"
#include "latsim/display/persistence.hpp"
#include "latsim/display/raster_timing.hpp"

namespace latsim::pipelines::analytic {

/// Frames enumerated at most, over all phase points.
inline constexpr int64_t kMaxFrames = 2'000'000;

/// Phases of one clock relative to the display, in non-decreasing order: one
/// fixed phase, or the midpoints of n equal steps of a period (a phase point
/// each), with their running sums.
class PhaseSet {
 public:
  static PhaseSet fixed(des::Time phase);
  /// floor(period * (2i + 1) / (2n)) ticks for i = 0 .. n - 1.
  static PhaseSet midpoints(des::Time period, int64_t n);

  int64_t size() const { return static_cast<int64_t>(ticks_.size()); }
  des::Time at(int64_t i) const { return des::Time::ps(ticks_[static_cast<size_t>(i)]); }
  /// Sum of the phases i in [lo, hi), in ticks.
  __int128 sum(int64_t lo, int64_t hi) const { return prefix_[static_cast<size_t>(hi)] - prefix_[static_cast<size_t>(lo)]; }
  /// How many phases are at or before `t` (they come first).
  int64_t count_at_or_before(des::Time t) const;

 private:
  explicit PhaseSet(std::vector<int64_t> ticks);
  std::vector<int64_t> ticks_;
  std::vector<__int128> prefix_;  // prefix_[i]: sum of the first i phases
};

/// Measured times (of the newest sample) at one frame over a set of phase points.
struct Measured {
  __int128 sum = 0;
  int64_t count = 0;
  des::Time min = des::Time::max(), max = -des::Time::max();

  /// Adds the phases [lo, hi) of `phases`, each measured at its phase + `offset`.
  void add_phases(const PhaseSet& phases, int64_t lo, int64_t hi, des::Time offset);
};

/// The per-line motion-to-photon latencies of the frames enumerated, summed
/// exactly in picoseconds, and how the enumeration ended.
struct GridTally {
  __int128 sum = 0;  ///< of (photon time - measured time) over every displayed line
  int64_t count = 0;  ///< lines
  des::Time min = des::Time::max(), max = -des::Time::max();
  int64_t frames = 0;            ///< frames enumerated, over every phase point (a cut-off frame counts)
  int64_t frames_per_point = 0;  ///< frames of one phase point's cycle (unknown past kMaxFrames: 0)
  bool truncated = false;        ///< the budget of fields ran out

  double mean_ms() const { return static_cast<double>(sum) / static_cast<double>(count) * 1e-9; }
  double min_ms() const { return min.to_ms(); }
  double max_ms() const { return max.to_ms(); }
};

/// The double-buffered system under every combination of a set of tracker
/// phases and a set of poll timer phases (the tracker's outer, the poll's
/// inner, as phase points are taken in turn). The renderer starts at the
/// first retrace with a sample and then at each swap; a frame rendered from
/// field s reads the newest sample visible at s's retrace (ready at its time
/// + delay; polled: at the last poll at or before the retrace) and is shown
/// from its swap, the first retrace at or after its render time, until the
/// next swap.
struct PhaseGrid {
  const display::RasterTiming& timing;
  des::Time render_time;
  des::RationalSeconds tracker_period;
  des::Time delay;  ///< from a sample's time until the host may see it
  PhaseSet tracker_phases;
  std::optional<des::RationalSeconds> poll_period;  ///< none: every sample is seen once ready
  PhaseSet poll_phases;  ///< one, ignored, without a poll timer

  /// The field a frame rendered from field `start_field` is first shown in.
  int64_t swap_after(int64_t start_field) const;
  /// The newest sample index visible at `retrace` to the first phase point.
  int64_t newest_sample_index(des::Time retrace) const;

  /// For every phase point in turn, the frames from field `first` whose start
  /// lies fewer than `fields` fields after it, each adding its shown fields'
  /// lines lit as `persistence` lights them: frames stop after kMaxFrames in
  /// all, and fields after `max_fields` (mid-frame: that frame is cut off and
  /// the enumeration ends, truncated). Exactly the sums, extremes and counts
  /// of taking phase point after phase point and frame after frame; the work
  /// is the frames of one phase point times the poll phases, each a few
  /// divisions.
  GridTally enumerate(int64_t first, int64_t fields, const display::PersistenceParams& persistence,
                      int64_t max_fields) const;

  /// The latest cutoff at or before `retrace` for poll phase j (the retrace
  /// itself without a poll timer), less the delay: samples measured by then are seen.
  des::Time ready_by(des::Time retrace, int64_t j) const;
};

}  // namespace latsim::pipelines::analytic
