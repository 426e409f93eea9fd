// The event budget: a run's event count estimated before it starts, from the
// rates its models and pipeline declare, and refused past a limit with the
// key that drives it (docs/event-budget.md).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/sections/shared.hpp"
#include "latsim/pipelines/pipeline.hpp"

namespace latsim::run {

/// What a run is expected to execute: every declared rate times the simulated duration.
struct EventEstimate {
  double duration_s = 0.0;
  double events = 0.0;         ///< events and steps of work together
  double events_only = 0.0;    ///< what summary.json's "events" should come near
  std::string dominant;        ///< the key whose rates add up to the most
  double dominant_share = 0.0; ///< of `events`, the dominant key's
  std::vector<pipelines::EventRate> rates;

  /// For summary.json: the totals, the dominant key and every rate.
  nlohmann::json to_json() const;
};

/// Sums the shared models' rates and the pipeline's over p.duration_s.
EventEstimate estimate_events(const sections::SharedParams& p, const pipelines::Pipeline& pipeline);

/// Throws scenario::ScenarioError at the dominant key when the estimate is
/// above `max_events` ("about 1.0e13 events over 10 s (limit 2e9; --max-events
/// raises it)"); max_events 0: no limit.
void check_event_budget(const EventEstimate& estimate, double max_events);

/// A count for a message: "1.0e13", "2e9", "3.5e6".
std::string count_text(double x, int decimals);

}  // namespace latsim::run
