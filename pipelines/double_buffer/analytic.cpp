#include "double_buffer/analytic.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "double_buffer/phase_grid.hpp"
#include "latsim/des/run_clocks.hpp"
#include "latsim/display/display.hpp"

namespace latsim::pipelines {

namespace analytic {

using i128 = __int128;

std::optional<Link> link_of(const AnalyticInputs& in) {
  Link l;
  l.delay = in.tracker_delay;
  if (const auto* serial = dynamic_cast<const tracker::SerialLink*>(in.transport)) {
    const auto& sp = serial->params();
    // Records that queue on the line or handlers that back up need the event model.
    if (serial->transmit_time() > des::PeriodicSchedule(des::Time::zero(), in.tracker_period).nominal_period())
      return std::nullopt;
    if (sp.host_mode == tracker::SerialLinkParams::Interrupt && sp.per_char_interrupt_cost > des::Time::zero())
      return std::nullopt;
    l.delay = l.delay + serial->transmit_time();
    l.name = "serial interrupt";
    if (sp.host_mode == tracker::SerialLinkParams::Poll) {
      l.name = "serial poll";
      l.poll = tracker::exact_period(sp.poll_interval);
    }
  } else if (!dynamic_cast<const tracker::DirectLink*>(in.transport)) {
    return std::nullopt;
  }
  return l;
}

namespace {

// Least common multiple of two positive rationals (reduced), if it fits.
std::optional<des::RationalSeconds> rational_lcm(des::RationalSeconds x, des::RationalSeconds y) {
  auto reduce = [](des::RationalSeconds r) {
    const int64_t g = std::gcd(r.num, r.den);
    return des::RationalSeconds{r.num / g, r.den / g};
  };
  x = reduce(x);
  y = reduce(y);
  // lcm(a/b, c/d) = lcm(a, c) / gcd(b, d) for reduced fractions.
  const i128 num = static_cast<i128>(x.num / std::gcd(x.num, y.num)) * y.num;
  const int64_t den = std::gcd(x.den, y.den);
  if (num > std::numeric_limits<int64_t>::max()) return std::nullopt;
  return des::RationalSeconds{static_cast<int64_t>(num), den};
}

}  // namespace

std::optional<int64_t> cycle_fields(des::RationalSeconds field, int64_t m, std::optional<des::RationalSeconds> tracker,
                                    std::optional<des::RationalSeconds> poll, int64_t max_frames, double& cycle_s) {
  std::optional<des::RationalSeconds> h = des::RationalSeconds{field.num * m, field.den};
  if (tracker) h = rational_lcm(*h, *tracker);
  if (h && poll) h = rational_lcm(*h, *poll);
  if (!h) return std::nullopt;
  cycle_s = h->to_seconds();
  // hyper / field, exact: the cycle is a whole number of fields.
  const i128 n = static_cast<i128>(h->num) * field.den;
  const i128 d = static_cast<i128>(h->den) * field.num;
  if (n % d != 0 || n / d > max_frames * 64) return std::nullopt;
  return static_cast<int64_t>(n / d);
}

}  // namespace analytic

namespace {

using analytic::Link;
using analytic::PhaseGrid;
using analytic::PhaseSet;

std::optional<int64_t> cycle_fields(des::RationalSeconds field, int64_t m, std::optional<des::RationalSeconds> tracker,
                                    std::optional<des::RationalSeconds> poll, double& cycle_s) {
  return analytic::cycle_fields(field, m, tracker, poll, analytic::kMaxFrames, cycle_s);
}

void set_latency(AnalyticLatency& a, const analytic::GridTally& tally) {
  a.frames = tally.frames;
  a.min_ms = tally.min_ms();
  a.mean_ms = tally.mean_ms();
  a.max_ms = tally.max_ms();
}

// Fixed phases: one repeat cycle of the run's own phases, frame after frame.
std::optional<AnalyticLatency> enumerate_fixed(const AnalyticInputs& in, const Link& link) {
  const display::RasterTiming timing(in.raster, in.display_phase);
  PhaseGrid grid{timing, in.render_time, in.tracker_period, link.delay, PhaseSet::fixed(in.tracker_phase),
                 link.poll, link.poll ? PhaseSet::fixed(in.poll_phase) : PhaseSet::fixed(des::Time::zero())};
  // Samples measured before the run began do not exist.
  const int64_t first_sample = des::PeriodicSchedule(in.tracker_phase, in.tracker_period).index_at_or_after(des::Time::zero());
  int64_t s = timing.field_at_or_after(des::Time::zero());
  const int64_t limit = s + 1'000'000;
  while (grid.newest_sample_index(timing.field_start(s)) < first_sample)
    if (++s > limit) return std::nullopt;
  AnalyticLatency a;
  const auto fields = cycle_fields(in.raster.field_period, grid.swap_after(s) - s, in.tracker_period, link.poll,
                                   a.hyperperiod_s);
  if (!fields) return std::nullopt;
  const analytic::GridTally tally = grid.enumerate(s, *fields, in.persistence, in.max_fields);
  a.complete = tally.frames == tally.frames_per_point && !tally.truncated;
  a.method = "phase enumeration over one repeat cycle of the fixed phases (no events)";
  set_latency(a, tally);
  return a;
}

// Integrated phases: relative phases on a grid of midpoints; where every
// relative phase is integrated each steady-state frame is alike, so one frame
// per grid point suffices, otherwise a repeat cycle of the fixed ones.
std::optional<AnalyticLatency> integrate(const AnalyticInputs& in, const Link& link) {
  const display::RasterTiming timing(in.raster, des::Time::zero());
  const bool poll_integrated = link.poll && in.integrate_poll;
  const bool stationary = in.integrate_tracker && (!link.poll || in.integrate_poll);
  AnalyticLatency a;
  a.phase_grid = stationary ? (link.poll ? 256 : 4096) : 64;
  const des::Time tracker_step = des::PeriodicSchedule(des::Time::zero(), in.tracker_period).nominal_period();
  const des::Time poll_step = link.poll ? des::PeriodicSchedule(des::Time::zero(), *link.poll).nominal_period() : des::Time{};
  PhaseGrid grid{timing,
                 in.render_time,
                 in.tracker_period,
                 link.delay,
                 in.integrate_tracker ? PhaseSet::midpoints(tracker_step, a.phase_grid)
                                      : PhaseSet::fixed(in.tracker_phase - in.display_phase),
                 link.poll,
                 poll_integrated ? PhaseSet::midpoints(poll_step, a.phase_grid)
                                 : PhaseSet::fixed(link.poll ? in.poll_phase - in.display_phase : des::Time::zero())};
  const int64_t m = grid.swap_after(0);
  std::optional<int64_t> fields = 1;
  if (!stationary) {
    fields = cycle_fields(in.raster.field_period, m, in.integrate_tracker ? std::nullopt : std::optional(in.tracker_period),
                          poll_integrated ? std::nullopt : link.poll, a.hyperperiod_s);
    if (!fields) return std::nullopt;
  }
  const analytic::GridTally tally = grid.enumerate(0, *fields, in.persistence, in.max_fields);
  a.complete = tally.frames < analytic::kMaxFrames && !tally.truncated;
  a.method = std::string("integrated over the phase") + (in.integrate_tracker && poll_integrated ? "s" : "") +
             " of the " + (in.integrate_tracker ? "tracker" : "") + (in.integrate_tracker && poll_integrated ? " and the " : "") +
             (poll_integrated ? "poll timer" : "") + " relative to the display (midpoints of " +
             std::to_string(a.phase_grid) + " steps per period; no events)";
  set_latency(a, tally);
  return a;
}

}  // namespace

std::optional<AnalyticLatency> analytic_double_buffer(const AnalyticInputs& in) {
  if (in.tracker_jitter > des::Time::zero() || in.transport == nullptr) return std::nullopt;
  const auto link = analytic::link_of(in);
  if (!link) return std::nullopt;
  const bool integrated = in.integrate_tracker || (link->poll && in.integrate_poll);
  auto a = integrated ? integrate(in, *link) : enumerate_fixed(in, *link);
  if (a) a->link = link->name;
  return a;
}

AnalyticInputs analytic_inputs(const RunContext& ctx, des::Time render_time) {
  const des::Clock* display = ctx.clocks.find("display");
  const des::Clock* tracker = ctx.clocks.find("tracker");
  const des::Clock* poll = ctx.clocks.find("poll");
  auto varies = [](const des::Clock* c) { return c && (c->drawn || c->rate_error_ppm != 0.0); };
  AnalyticInputs in;
  in.raster = ctx.display_params.raster;  // the nominal periods
  in.persistence = ctx.display.persistence().params();
  in.tracker_period = ctx.tracker.period;
  in.tracker_delay = ctx.tracker.internal_delay;
  in.tracker_jitter = ctx.tracker.jitter;
  in.transport = &ctx.transport;
  in.render_time = render_time;
  in.display_phase = display ? display->phase : des::Time::zero();
  in.tracker_phase = tracker ? tracker->phase : des::Time::zero();
  in.poll_phase = poll ? poll->phase : des::Time::zero();
  in.integrate_tracker = varies(tracker) || varies(display);
  in.integrate_poll = poll && (varies(poll) || varies(display));
  // As many fields as the run itself scans out, within bounds: enough for
  // every repeat cycle a real configuration has, and never minutes of work.
  const double run_fields = ctx.duration.to_seconds() / in.raster.field_period.to_seconds();
  in.max_fields = static_cast<int64_t>(std::clamp(run_fields, 4e6, 4e7));
  return in;
}

}  // namespace latsim::pipelines
