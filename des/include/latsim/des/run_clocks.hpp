// The independent clocks of one run and the phases they were given.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "latsim/des/clock.hpp"

namespace latsim::des {

/// Resolves every clock of a run (tracker, poll timer, display, a pipeline's
/// host loop): a phase the scenario fixes is kept, any other is drawn from
/// the clock's own stream "clock.<name>" of the run seed and replication, and
/// each phase used is remembered with the JSON pointer of its key so that
/// the resolved scenario reproduces the run.
class RunClocks {
 public:
  RunClocks(uint64_t seed, uint64_t replication) : seed_(seed), replication_(replication) {}

  /// Resolves clock `name` whose phase key lives at `phase_pointer`. The
  /// settings are only read: the phase used is the returned clock's (and
  /// phases_ms()'s), decided here once. The reference stays valid.
  const des::Clock& resolve(const std::string& name, const std::string& phase_pointer, des::RationalSeconds nominal,
                            const des::ClockSettings& settings);
  /// The clock called `name`, or nullptr when the run has none.
  const des::Clock* find(const std::string& name) const;
  const std::deque<des::Clock>& all() const { return clocks_; }
  /// (JSON pointer, phase in ms) of every clock resolved.
  const std::vector<std::pair<std::string, double>>& phases_ms() const { return phases_ms_; }

 private:
  uint64_t seed_;
  uint64_t replication_;
  std::deque<des::Clock> clocks_;
  std::vector<std::pair<std::string, double>> phases_ms_;
};

}  // namespace latsim::des
