// Independent oscillators: each clock of a simulated system has its own phase
// and its own small rate error, so that no two clocks are locked together by
// accident of the model.
#pragma once

#include <optional>
#include <string>

#include "latsim/des/random.hpp"
#include "latsim/des/time.hpp"

namespace latsim::des {

/// A clock as a scenario describes it: a fixed phase, or none (then drawn per
/// replication), and how far its rate is off the nominal one.
struct ClockSettings {
  std::optional<Time> phase;    ///< time of tick 0; absent: drawn uniformly over one period
  double rate_error_ppm = 0.0;  ///< frequency = nominal x (1 + ppm x 1e-6)
};

/// The exact period of a clock whose frequency is off by `rate_error_ppm`:
/// nominal x 1e9 / (1e9 + ppb), with the error rounded to a part per billion,
/// reduced. Throws std::invalid_argument when |ppm| > 1e5 or the result does
/// not fit 64-bit numerator and denominator.
RationalSeconds period_with_rate_error(RationalSeconds nominal, double rate_error_ppm);

/// A clock as a run uses it: its actual period and phase, and where they came from.
struct Clock {
  std::string name;             ///< "tracker", "display", "poll", "loop"
  RationalSeconds nominal;      ///< the period the scenario names
  RationalSeconds period;       ///< the period with the rate error applied
  Time phase;                   ///< time of tick 0, in [0, one period) when drawn
  bool drawn = false;           ///< the phase came from the clock's own random stream
  double rate_error_ppm = 0.0;

  PeriodicSchedule schedule() const { return PeriodicSchedule(phase, period); }
  /// The settings of this clock as resolved (its phase fixed): what a model
  /// that reads its clock from its parameters is built with.
  ClockSettings settings() const { return ClockSettings{phase, rate_error_ppm}; }
};

/// Resolves a clock: a fixed phase is kept; otherwise the phase is drawn
/// uniformly over the integer ticks of one actual period from `stream`.
Clock resolve_clock(std::string name, RationalSeconds nominal, const ClockSettings& settings, RandomStream& stream);

}  // namespace latsim::des
