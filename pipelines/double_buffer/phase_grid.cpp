#include "double_buffer/phase_grid.hpp"

#include <algorithm>

namespace latsim::pipelines::analytic {

namespace {

using i128 = __int128;

/// Every field lights the same lines at the same offsets from its retrace
/// (the middle of each line's lit interval under the display's persistence:
/// the line's scanout instant on an impulse display, a constant later on full
/// or rolling persistence, one instant after the field's last line for a
/// global flash), so a field shown for a frame adds lines x (retrace -
/// measured) + the sum of the offsets.
struct FieldLines {
  int lines = 0;
  i128 offsets_sum = 0;
  des::Time first = des::Time::max(), last = -des::Time::max();

  FieldLines(const display::RasterTiming& t, const display::PersistenceParams& persistence) : lines(t.lines_per_field()) {
    const display::Persistence lit(persistence, t);
    for (int j = 0; j < lines; ++j) {
      const des::Time offset = lit.lit(0, t.line_time(0, j)).middle() - t.field_start(0);
      offsets_sum += offset.ticks();
      first = std::min(first, offset);
      last = std::max(last, offset);
    }
  }
};

/// One frame of a phase point: rendered from field `start`, shown in fields [shown, next).
struct FrameWalk {
  const PhaseGrid& grid;
  int64_t start, shown, next;

  FrameWalk(const PhaseGrid& g, int64_t first) : grid(g), start(first), shown(g.swap_after(first)), next(g.swap_after(shown)) {}
  int64_t fields() const { return next - shown; }
  void advance() {
    start = shown;
    shown = next;
    next = grid.swap_after(shown);
  }
};

/// Adds `n` shown fields from field `f0` of a frame, for phase points whose measured times are `m`.
void add_fields(GridTally& t, const FieldLines& lines, const display::RasterTiming& timing, int64_t f0, int64_t n,
                const Measured& m) {
  if (n <= 0 || m.count == 0) return;
  i128 retraces = 0;
  for (int64_t f = f0; f < f0 + n; ++f) retraces += timing.field_start(f).ticks();
  const i128 points = m.count;
  t.sum += points * (lines.lines * retraces + n * lines.offsets_sum) - static_cast<i128>(lines.lines) * n * m.sum;
  t.count += m.count * n * lines.lines;
  // Over the phase points the newest sample closest to the retrace gives the least latency.
  t.min = std::min(t.min, (timing.field_start(f0) - m.max) + lines.first);
  t.max = std::max(t.max, (timing.field_start(f0 + n - 1) - m.min) + lines.last);
}

int64_t ceil_div(int64_t a, int64_t b) { return a / b + (a % b != 0 ? 1 : 0); }

/// The tracker's samples as every phase of a set takes them: sample k of the
/// tracker at phase p is measured at p + at(k) of the schedule from zero.
class NewestSamples {
 public:
  NewestSamples(des::RationalSeconds period, const PhaseSet& phases)
      : schedule_(des::Time::zero(), period),
        phases_(phases),
        one_by_one_(phases.at(phases.size() - 1) - phases.at(0) >= schedule_.nominal_period()) {}

  /// Adds the measured time of the newest sample ready by `ready_by` for the phases [lo, hi).
  void add(des::Time ready_by, int64_t lo, int64_t hi, Measured& m) const {
    if (lo >= hi) return;
    if (one_by_one_) {
      // Phases a period or more apart (a grid finer than the tick can hold): one by one.
      for (int64_t i = lo; i < hi; ++i)
        m.add_phases(phases_, i, i + 1, schedule_.at(schedule_.index_at_or_before(ready_by - phases_.at(i))));
      return;
    }
    // The earliest phase sees the newest sample k0; a later phase p sees it
    // while p + at(k0) <= ready_by and otherwise sample k0 - 1, because the
    // phases span less than the shortest period, floor(period) = at(1) - at(0).
    const int64_t k0 = schedule_.index_at_or_before(ready_by - phases_.at(lo));
    const des::Time newest = schedule_.at(k0);
    const int64_t split = std::clamp(phases_.count_at_or_before(ready_by - newest), lo, hi);
    m.add_phases(phases_, lo, split, newest);
    if (split < hi) m.add_phases(phases_, split, hi, schedule_.at(k0 - 1));
  }

 private:
  des::PeriodicSchedule schedule_;
  const PhaseSet& phases_;
  bool one_by_one_;
};

}  // namespace

PhaseSet::PhaseSet(std::vector<int64_t> ticks) : ticks_(std::move(ticks)), prefix_(ticks_.size() + 1, 0) {
  for (size_t i = 0; i < ticks_.size(); ++i) prefix_[i + 1] = prefix_[i] + ticks_[i];
}

PhaseSet PhaseSet::fixed(des::Time phase) { return PhaseSet({phase.ticks()}); }

PhaseSet PhaseSet::midpoints(des::Time period, int64_t n) {
  // floor(P (2i + 1) / 2n) stepped without dividing: the numerator grows by 2P
  // a step, so the quotient by 2P div 2n and the remainder by 2P mod 2n.
  const i128 p = period.ticks(), d = 2 * static_cast<i128>(n);
  const i128 step_q = 2 * p / d, step_r = 2 * p % d;
  i128 q = p / d, r = p % d;
  std::vector<int64_t> ticks(static_cast<size_t>(n));
  for (auto& t : ticks) {
    t = static_cast<int64_t>(q);
    q += step_q;
    r += step_r;
    if (r >= d) {
      r -= d;
      ++q;
    }
  }
  return PhaseSet(std::move(ticks));
}

int64_t PhaseSet::count_at_or_before(des::Time t) const {
  return std::upper_bound(ticks_.begin(), ticks_.end(), t.ticks()) - ticks_.begin();
}

void Measured::add_phases(const PhaseSet& phases, int64_t lo, int64_t hi, des::Time offset) {
  if (lo >= hi) return;
  sum += phases.sum(lo, hi) + static_cast<i128>(hi - lo) * offset.ticks();
  count += hi - lo;
  min = std::min(min, phases.at(lo) + offset);
  max = std::max(max, phases.at(hi - 1) + offset);
}

int64_t PhaseGrid::swap_after(int64_t start_field) const {
  if (render_time == des::Time::zero()) return start_field + 1;
  return std::max(start_field + 1, timing.field_at_or_after(timing.field_start(start_field) + render_time));
}

des::Time PhaseGrid::ready_by(des::Time retrace, int64_t j) const {
  if (!poll_period) return retrace - delay;
  const des::PeriodicSchedule polls(poll_phases.at(j), *poll_period);
  return polls.at(polls.index_at_or_before(retrace)) - delay;
}

int64_t PhaseGrid::newest_sample_index(des::Time retrace) const {
  return des::PeriodicSchedule(tracker_phases.at(0), tracker_period).index_at_or_before(ready_by(retrace, 0));
}

namespace {

/// Where the enumeration of the phase points (g = tracker index x poll phases
/// + poll index, frames q of each in turn) ends.
struct Stop {
  int64_t frames_per_point = 0;  // F; 0 when above kMaxFrames (only point 0 is reached)
  int64_t frames = 0;            // frames enumerated, the cut-off one included
  bool truncated = false;
  int64_t last_point = 0, last_frame = 0, last_fields = 0;  // the cut-off frame and its fields

  /// Phase points that enumerate frame q in full.
  int64_t points_of_frame(int64_t q, int64_t points) const {
    const int64_t full = truncated ? frames - 1 : frames;
    if (full <= q) return 0;
    return frames_per_point == 0 ? 1 : std::min(points, ceil_div(full - q, frames_per_point));
  }
};

Stop stop_of(const PhaseGrid& grid, int64_t first, int64_t fields, int64_t max_fields) {
  // One phase point's frames: how many, their fields, and the first whose end passes the budget.
  Stop stop;
  int64_t count = 0, total_fields = 0, over_frame = -1, over_start = 0;
  bool capped = false;
  if (fields <= 0) return stop;
  for (FrameWalk w(grid, first); w.start - first < fields; w.advance()) {
    if (count == kMaxFrames) {
      capped = true;
      break;
    }
    if (over_frame < 0 && total_fields + w.fields() > max_fields) {
      over_frame = count;
      over_start = total_fields;
    }
    total_fields += w.fields();
    ++count;
  }
  const int64_t points = grid.tracker_phases.size() * (grid.poll_period ? grid.poll_phases.size() : 1);
  stop.frames_per_point = capped ? 0 : count;
  stop.frames = capped ? kMaxFrames : std::min(points * count, kMaxFrames);
  // The phase point and frame during which the fields run out, if any.
  int64_t cut_point = 0, cut_frame = over_frame, cut_start = over_start;
  if (!capped && over_frame < 0) {
    cut_point = max_fields / total_fields;
    const int64_t rest = max_fields % total_fields;
    int64_t q = 0, start = 0;
    for (FrameWalk w(grid, first); start + w.fields() <= rest; w.advance(), ++q) start += w.fields();
    cut_frame = q;
    cut_start = cut_point * total_fields + start;
  }
  if (cut_frame < 0 || cut_point >= points) return stop;
  const int64_t cut = cut_point * count + cut_frame;  // its position among all frames
  if (cut >= stop.frames) return stop;
  stop.frames = cut + 1;
  stop.truncated = true;
  stop.last_point = cut_point;
  stop.last_frame = cut_frame;
  stop.last_fields = max_fields - cut_start;
  return stop;
}

}  // namespace

GridTally PhaseGrid::enumerate(int64_t first, int64_t fields, const display::PersistenceParams& persistence,
                               int64_t max_fields) const {
  const FieldLines lines(timing, persistence);
  const Stop stop = stop_of(*this, first, fields, max_fields);
  const NewestSamples samples(tracker_period, tracker_phases);
  const int64_t polls = poll_period ? poll_phases.size() : 1;
  const int64_t points = tracker_phases.size() * polls;
  GridTally tally;
  tally.frames = stop.frames;
  tally.frames_per_point = stop.frames_per_point;
  tally.truncated = stop.truncated;
  std::vector<des::Time> ready(static_cast<size_t>(polls));
  FrameWalk w(*this, first);
  for (int64_t q = 0; q < stop.frames && (stop.frames_per_point == 0 || q < stop.frames_per_point); ++q, w.advance()) {
    const int64_t full = stop.points_of_frame(q, points);
    const bool cut = stop.truncated && q == stop.last_frame;
    if (full == 0 && !cut) continue;
    const des::Time retrace = timing.field_start(w.start);
    for (int64_t j = 0; j < polls; ++j) ready[static_cast<size_t>(j)] = ready_by(retrace, j);
    // Points [0, full): whole rows of poll phases for the first tracker phases, then part of the next row.
    Measured m;
    const int64_t rows = full / polls, rest = full % polls;
    for (int64_t j = 0; j < polls; ++j) {
      samples.add(ready[static_cast<size_t>(j)], 0, rows, m);
      if (j < rest) samples.add(ready[static_cast<size_t>(j)], rows, rows + 1, m);
    }
    add_fields(tally, lines, timing, w.shown, w.fields(), m);
    if (cut) {
      Measured last;
      const int64_t i = stop.last_point / polls, j = stop.last_point % polls;
      samples.add(ready[static_cast<size_t>(j)], i, i + 1, last);
      add_fields(tally, lines, timing, w.shown, stop.last_fields, last);
    }
  }
  return tally;
}

}  // namespace latsim::pipelines::analytic
