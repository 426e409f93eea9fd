#include "latsim/results/link_figures.hpp"

#include <cstdio>

#include "fixed_text.hpp"

namespace latsim::results {

void LinkFigures::record_carried(const tracker::TrackerSample& s, const tracker::Carriage& c, bool line) {
  ++records_offered_;
  figures_.add(to_host_, "tracker_to_host_ms", (c.visible - s.measured_at).to_ms());
  if (line) figures_.add(line_wait_, "line_wait_ms", (c.start - s.ready_at).to_ms());
  if (ledger_.on()) ledger_.carried(s, c);
}

void LinkFigures::finish(const RunTotals& t) {
  if (t.line_occupancy <= des::Time::zero()) return;
  const double duration_s = t.duration.to_seconds();
  const double utilisation = static_cast<double>(records_offered_ + t.records_dropped + t.records_waiting) *
                             t.line_occupancy.to_seconds() / duration_s;
  figures_.set("records_dropped", t.records_dropped);
  figures_.set("line_utilisation", utilisation);
  // A line exactly as fast as the tracker (32 bytes at 19200 baud, 60 Hz) is
  // busy all the time but keeps up: only rounding to the picosecond would
  // put it above 1.
  constexpr double kRounding = 1e-9;
  if (utilisation > 1.0 + kRounding || t.records_dropped > 0)
    figures_.warn("serial line overloaded: " + t.link_description + " take " + fixed(t.line_occupancy.to_ms(), 3) +
                  " ms each, the tracker sends one every " + fixed(t.tracker_period.to_ms(), 3) +
                  " ms (line_utilisation " + fixed(utilisation, 3) + "); " + std::to_string(t.records_dropped) +
                  " records dropped from a buffer of " + std::to_string(t.buffer_records));
  if (t.handler_time <= des::Time::zero()) return;
  const double handlers = static_cast<double>(records_offered_) * t.handler_time.to_seconds() / duration_s;
  figures_.set("interrupt_utilisation", handlers);
  if (handlers > 1.0 + kRounding)
    figures_.warn("interrupt handlers overloaded: " + fixed(t.handler_time.to_ms(), 3) + " ms of handlers per record (" +
                  "interrupt_utilisation " + fixed(handlers, 3) + "); the host falls further behind with every record");
}

}  // namespace latsim::results
