#include "double_buffer/analytic.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

namespace latsim::pipelines {

namespace {

/// Newest sample index visible at time r, or nullopt. Closed form per link:
/// direct: ready = t_k + D; serial: complete = t_k + D + X; polled: the last
/// poll at or before r delivers everything complete by then.
struct Visibility {
  des::PeriodicSchedule samples;
  des::Time delay;                  // D (+ X for serial)
  std::optional<des::PeriodicSchedule> polls;
  int64_t first_index = 0;

  std::optional<int64_t> newest(des::Time r) const {
    des::Time cutoff = r;
    if (polls) cutoff = polls->at(polls->index_at_or_before(r));
    const int64_t k = samples.index_at_or_before(cutoff - delay);
    if (k < first_index) return std::nullopt;
    return k;
  }
};

// Least common multiple of two positive rationals a/b and c/d (reduced).
std::optional<des::RationalSeconds> rational_lcm(des::RationalSeconds x, des::RationalSeconds y) {
  auto reduce = [](des::RationalSeconds r) {
    const int64_t g = std::gcd(r.num, r.den);
    return des::RationalSeconds{r.num / g, r.den / g};
  };
  x = reduce(x);
  y = reduce(y);
  // lcm(a/b, c/d) = lcm(a, c) / gcd(b, d) for reduced fractions.
  const __int128 num = static_cast<__int128>(x.num / std::gcd(x.num, y.num)) * y.num;
  const int64_t den = std::gcd(x.den, y.den);
  if (num > std::numeric_limits<int64_t>::max()) return std::nullopt;
  return des::RationalSeconds{static_cast<int64_t>(num), den};
}

}  // namespace

std::optional<AnalyticLatency> analytic_double_buffer(const display::RasterTiming& timing,
                                                     const tracker::TrackerParams& tp,
                                                     const tracker::Transport& transport, des::Time render_time) {
  if (tp.jitter > des::Time::zero()) return std::nullopt;
  Visibility vis{des::PeriodicSchedule(tp.phase, tp.period), tp.internal_delay, std::nullopt, 0};
  vis.first_index = vis.samples.index_at_or_after(des::Time::zero());
  des::RationalSeconds hyper = timing.params().field_period;
  if (!(hyper = *rational_lcm(hyper, tp.period)).num) return std::nullopt;
  std::string link = "direct";
  if (const auto* serial = dynamic_cast<const tracker::SerialLink*>(&transport)) {
    const auto& sp = serial->params();
    // Records that queue on the line or handlers that back up need the event model.
    if (serial->transmit_time() > vis.samples.nominal_period()) return std::nullopt;
    if (sp.host_mode == tracker::SerialLinkParams::Interrupt && sp.per_char_interrupt_cost > des::Time::zero())
      return std::nullopt;
    vis.delay = vis.delay + serial->transmit_time();
    link = "serial interrupt";
    if (sp.host_mode == tracker::SerialLinkParams::Poll) {
      link = "serial poll";
      // Poll intervals are whole picoseconds: an exact rational.
      const des::RationalSeconds poll{sp.poll_interval.ticks(), des::Time::kTicksPerSecond};
      vis.polls = des::PeriodicSchedule(sp.poll_phase, poll);
      const auto h = rational_lcm(hyper, poll);
      if (!h) return std::nullopt;
      hyper = *h;
    }
  } else if (!dynamic_cast<const tracker::DirectLink*>(&transport)) {
    return std::nullopt;
  }

  // The renderer starts at the first retrace with a sample, and afterwards at
  // each swap; an image is shown from its swap until the next one.
  const int lines = timing.lines_per_field();
  int64_t s = 0;
  while (!vis.newest(timing.field_start(s))) {
    if (++s > 1'000'000) return std::nullopt;
  }
  auto swap_after = [&](int64_t start_field) {
    if (render_time == des::Time::zero()) return start_field + 1;
    return std::max(start_field + 1, timing.field_at_or_after(timing.field_start(start_field) + render_time));
  };
  // Frames start every m fields: the phases repeat after the lcm with m fields too.
  const int64_t m = swap_after(s) - s;
  const des::RationalSeconds field = timing.params().field_period;
  const auto h = rational_lcm(hyper, des::RationalSeconds{field.num * m, field.den});
  if (!h) return std::nullopt;
  hyper = *h;
  const des::Time origin = timing.field_start(s);
  const double hyper_s = hyper.to_seconds();
  constexpr int64_t kMaxFrames = 2'000'000;
  double min_ms = std::numeric_limits<double>::infinity(), max_ms = -min_ms, sum_ms = 0.0;
  int64_t count = 0, frames = 0;
  int64_t swap = swap_after(s);
  while (frames < kMaxFrames) {
    const des::Time r = timing.field_start(s);
    const des::Time measured = vis.samples.at(*vis.newest(r));
    const int64_t next_swap = swap_after(swap);
    for (int64_t f = swap; f < next_swap; ++f)
      for (int j = 0; j < lines; ++j) {
        const double ms = (timing.line_time(f, j) - measured).to_ms();
        min_ms = std::min(min_ms, ms);
        max_ms = std::max(max_ms, ms);
        sum_ms += ms;
        ++count;
      }
    ++frames;
    s = swap;
    swap = next_swap;
    // One whole hyperperiod of phases seen (and the frame pattern repeats).
    if ((timing.field_start(s) - origin).to_seconds() >= hyper_s) break;
  }
  return AnalyticLatency{link, hyper_s, frames, frames < kMaxFrames, min_ms, sum_ms / count, max_ms};
}

}  // namespace latsim::pipelines
