// The tracker's records on their way to the host.
#pragma once

#include <cstdint>
#include <string>

#include "latsim/des/time.hpp"
#include "latsim/results/figure_writer.hpp"
#include "latsim/results/ledger.hpp"
#include "latsim/stats/stats.hpp"
#include "latsim/tracker/tracker.hpp"
#include "latsim/tracker/transport.hpp"

namespace latsim::results {

/// What the run knows at its end about its shared models.
struct RunTotals {
  des::Time duration;
  int64_t fields = 0;            ///< retraces the display made
  int64_t tracker_samples = 0;   ///< samples measured
  des::Time tracker_period;      ///< actual sampling period (for overload messages)
  /// The link: records offered, dropped, still waiting; its occupancy, buffer and handler time per record.
  int64_t records_dropped = 0;
  int64_t records_waiting = 0;
  des::Time line_occupancy;      ///< zero: a link without a line (direct)
  int64_t buffer_records = 0;
  des::Time handler_time;        ///< interrupt handlers per record (zero: none modelled)
  std::string link_description;  ///< e.g. "40-byte records at 19200 baud"
};

/// Turns every record the link carries into tracker_to_host_ms (and, on a
/// serial line, line_wait_ms), and the run's totals into records_dropped,
/// line_utilisation and interrupt_utilisation, warning when the line or the
/// host cannot keep up.
class LinkFigures {
 public:
  LinkFigures(FigureWriter figures, Ledger& ledger) : figures_(std::move(figures)), ledger_(ledger) {}

  /// A record given to the link (`line`: a serial line, whose wait is reported).
  void record_carried(const tracker::TrackerSample& s, const tracker::Carriage& c, bool line);
  void finish(const RunTotals& totals);

 private:
  FigureWriter figures_;
  Ledger& ledger_;
  stats::Distribution* to_host_ = nullptr;
  stats::Distribution* line_wait_ = nullptr;
  int64_t records_offered_ = 0;
};

}  // namespace latsim::results
