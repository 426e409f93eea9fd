// The analytic figure of double buffering as it was first computed: every
// phase point of the grid and every frame enumerated one by one. Kept for
// tests only, as the reference that analytic_double_buffer() (which counts
// the tracker's phase points in blocks) must equal to the last bit; the link
// and the repeat cycle are the product's own (analytic::link_of, cycle_fields).
#include "analytic_reference.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

namespace latsim::pipelines::testing {

namespace {

using i128 = __int128;

constexpr int64_t kMaxFrames = 2'000'000;  // frames enumerated at most, over all phase points

using analytic::Link;
using analytic::link_of;

/// Newest sample visible at time r under one phase configuration: ready at
/// t_k + delay; polled: the last poll at or before r delivers what is ready then.
struct Visibility {
  des::PeriodicSchedule samples;
  des::Time delay;
  std::optional<des::PeriodicSchedule> polls;
  int64_t first_index = std::numeric_limits<int64_t>::min();  // no samples before the run

  std::optional<des::Time> newest_measured(des::Time r) const {
    des::Time cutoff = r;
    if (polls) cutoff = polls->at(polls->index_at_or_before(r));
    const int64_t k = samples.index_at_or_before(cutoff - delay);
    if (k < first_index) return std::nullopt;
    return samples.at(k);
  }
};

/// Per-line latencies summed exactly in picoseconds. Every field has the
/// same photon offsets of its lines from its retrace (the middle of each
/// line's lit interval under the display's persistence: the line's scanout
/// instant on an impulse display, a constant later on full or rolling
/// persistence, one instant after the field's last line for a global flash),
/// so a displayed field adds lines x (retrace - measured) + the sum of the
/// offsets. At most `max_fields` fields are taken: the work follows what the
/// run can afford, not the render time (one frame of a long render spans
/// many fields).
class Tally {
 public:
  Tally(const display::RasterTiming& t, const display::PersistenceParams& persistence, int64_t max_fields)
      : lines_(t.lines_per_field()), max_fields_(max_fields) {
    const display::Persistence lit(persistence, t);
    first_ = des::Time::max();
    last_ = -des::Time::max();
    for (int j = 0; j < lines_; ++j) {
      const des::Time offset = lit.lit(0, t.line_time(0, j)).middle() - t.field_start(0);
      offsets_sum_ += offset.ticks();
      first_ = std::min(first_, offset);
      last_ = std::max(last_, offset);
    }
  }
  /// False, and nothing added, once the budget of fields is spent.
  bool field(des::Time retrace, des::Time measured) {
    if (fields_ >= max_fields_) {
      truncated_ = true;
      return false;
    }
    ++fields_;
    const des::Time base = retrace - measured;
    sum_ += static_cast<i128>(lines_) * base.ticks() + offsets_sum_;
    count_ += lines_;
    min_ = std::min(min_, base + first_);
    max_ = std::max(max_, base + last_);
    return true;
  }
  double mean_ms() const { return static_cast<double>(sum_) / static_cast<double>(count_) * 1e-9; }
  double min_ms() const { return min_.to_ms(); }
  double max_ms() const { return max_.to_ms(); }
  bool empty() const { return count_ == 0; }
  bool truncated() const { return truncated_; }

 private:
  int lines_;
  i128 offsets_sum_ = 0;
  des::Time first_, last_;
  i128 sum_ = 0;
  int64_t count_ = 0;
  int64_t max_fields_;
  int64_t fields_ = 0;
  bool truncated_ = false;
  des::Time min_ = des::Time::max(), max_ = -des::Time::max();
};

/// The renderer starts at the first retrace with a sample and afterwards at
/// each swap; an image is shown from its swap until the next one.
struct Frames {
  const display::RasterTiming& timing;
  des::Time render_time;

  int64_t swap_after(int64_t start_field) const {
    if (render_time == des::Time::zero()) return start_field + 1;
    return std::max(start_field + 1, timing.field_at_or_after(timing.field_start(start_field) + render_time));
  }
  /// Adds the frame rendered at field s (shown from its swap until the next) and returns its swap.
  int64_t add(int64_t s, const Visibility& vis, Tally& tally) const {
    const des::Time measured = *vis.newest_measured(timing.field_start(s));
    const int64_t swap = swap_after(s), next = swap_after(swap);
    for (int64_t f = swap; f < next; ++f)
      if (!tally.field(timing.field_start(f), measured)) break;
    return swap;
  }
};

std::optional<int64_t> cycle_fields(des::RationalSeconds field, int64_t m, std::optional<des::RationalSeconds> tracker,
                                    std::optional<des::RationalSeconds> poll, double& cycle_s) {
  return analytic::cycle_fields(field, m, tracker, poll, kMaxFrames, cycle_s);
}

// Fixed phases: one repeat cycle of the run's own phases, frame after frame.
std::optional<AnalyticLatency> enumerate_fixed(const AnalyticInputs& in, const Link& link) {
  const display::RasterTiming timing(in.raster, in.display_phase);
  Visibility vis{des::PeriodicSchedule(in.tracker_phase, in.tracker_period), link.delay, std::nullopt, 0};
  vis.first_index = vis.samples.index_at_or_after(des::Time::zero());
  if (link.poll) vis.polls = des::PeriodicSchedule(in.poll_phase, *link.poll);
  const Frames frames{timing, in.render_time};
  int64_t s = timing.field_at_or_after(des::Time::zero());
  const int64_t limit = s + 1'000'000;
  while (!vis.newest_measured(timing.field_start(s)))
    if (++s > limit) return std::nullopt;
  AnalyticLatency a;
  const auto fields = cycle_fields(in.raster.field_period, frames.swap_after(s) - s, in.tracker_period, link.poll,
                                   a.hyperperiod_s);
  if (!fields) return std::nullopt;
  Tally tally(timing, in.persistence, in.max_fields);
  const int64_t s0 = s;
  while (s - s0 < *fields && a.frames < kMaxFrames && !tally.truncated()) {
    s = frames.add(s, vis, tally);
    ++a.frames;
  }
  a.complete = s - s0 >= *fields && !tally.truncated();
  a.method = "phase enumeration over one repeat cycle of the fixed phases (no events)";
  a.min_ms = tally.min_ms();
  a.mean_ms = tally.mean_ms();
  a.max_ms = tally.max_ms();
  return a;
}

// Integrated phases: relative phases on a grid of midpoints; where every
// relative phase is integrated each steady-state frame is alike, so one frame
// per grid point suffices, otherwise a repeat cycle of the fixed ones.
std::optional<AnalyticLatency> integrate(const AnalyticInputs& in, const Link& link) {
  const display::RasterTiming timing(in.raster, des::Time::zero());
  const Frames frames{timing, in.render_time};
  const bool poll_integrated = link.poll && in.integrate_poll;
  const bool stationary = in.integrate_tracker && (!link.poll || in.integrate_poll);
  AnalyticLatency a;
  a.phase_grid = stationary ? (link.poll ? 256 : 4096) : 64;
  const int64_t m = frames.swap_after(0);
  std::optional<int64_t> fields = 1;
  if (!stationary) {
    fields = cycle_fields(in.raster.field_period, m, in.integrate_tracker ? std::nullopt : std::optional(in.tracker_period),
                          poll_integrated ? std::nullopt : link.poll, a.hyperperiod_s);
    if (!fields) return std::nullopt;
  }
  const des::Time tracker_step = des::PeriodicSchedule(des::Time::zero(), in.tracker_period).nominal_period();
  const des::Time poll_step = link.poll ? des::PeriodicSchedule(des::Time::zero(), *link.poll).nominal_period() : des::Time{};
  // The midpoint of step i of a period divided into n.
  auto midpoint = [](des::Time period, int64_t i, int64_t n) {
    return des::Time::ps(static_cast<int64_t>((static_cast<i128>(period.ticks()) * (2 * i + 1)) / (2 * n)));
  };
  const int64_t nt = in.integrate_tracker ? a.phase_grid : 1;
  const int64_t np = poll_integrated ? a.phase_grid : 1;
  Tally tally(timing, in.persistence, in.max_fields);
  for (int64_t i = 0; i < nt; ++i)
    for (int64_t j = 0; j < np; ++j) {
      const des::Time tp = in.integrate_tracker ? midpoint(tracker_step, i, nt) : in.tracker_phase - in.display_phase;
      Visibility vis{des::PeriodicSchedule(tp, in.tracker_period), link.delay, std::nullopt};
      if (link.poll)
        vis.polls = des::PeriodicSchedule(poll_integrated ? midpoint(poll_step, j, np) : in.poll_phase - in.display_phase,
                                          *link.poll);
      for (int64_t s = 0; s < *fields && a.frames < kMaxFrames && !tally.truncated(); ++a.frames)
        s = frames.add(s, vis, tally);
    }
  a.complete = a.frames < kMaxFrames && !tally.truncated();
  a.method = std::string("integrated over the phase") + (in.integrate_tracker && poll_integrated ? "s" : "") +
             " of the " + (in.integrate_tracker ? "tracker" : "") + (in.integrate_tracker && poll_integrated ? " and the " : "") +
             (poll_integrated ? "poll timer" : "") + " relative to the display (midpoints of " +
             std::to_string(a.phase_grid) + " steps per period; no events)";
  a.min_ms = tally.min_ms();
  a.mean_ms = tally.mean_ms();
  a.max_ms = tally.max_ms();
  return a;
}

}  // namespace

std::optional<AnalyticLatency> reference_analytic_double_buffer(const AnalyticInputs& in) {
  if (in.tracker_jitter > des::Time::zero() || in.transport == nullptr) return std::nullopt;
  const auto link = link_of(in);
  if (!link) return std::nullopt;
  const bool integrated = in.integrate_tracker || (link->poll && in.integrate_poll);
  auto a = integrated ? integrate(in, *link) : enumerate_fixed(in, *link);
  if (a) a->link = link->name;
  return a;
}

}  // namespace latsim::pipelines::testing
