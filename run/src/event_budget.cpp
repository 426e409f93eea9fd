#include "latsim/run/event_budget.hpp"

#include <cmath>
#include <cstdio>
#include <map>

#include "latsim/scenario/config.hpp"

namespace latsim::run {

std::string count_text(double x, int decimals) {
  if (!std::isfinite(x)) return "more than 1e308";
  const int exponent = x > 0.0 ? static_cast<int>(std::floor(std::log10(x))) : 0;
  double mantissa = x / std::pow(10.0, exponent);
  int e = exponent;
  // Rounding may carry into the next power of ten ("10.0e12").
  if (std::round(mantissa * std::pow(10.0, decimals)) >= 10.0 * std::pow(10.0, decimals)) {
    mantissa /= 10.0;
    ++e;
  }
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*fe%d", decimals, mantissa, e);
  return buf;
}

nlohmann::json EventEstimate::to_json() const {
  nlohmann::json rates_json = nlohmann::json::array();
  for (const pipelines::EventRate& r : rates)
    rates_json.push_back({{"pointer", r.pointer}, {"model", r.model}, {"per_s", r.per_s}, {"steps", r.steps}});
  return {{"events", events}, {"events_without_steps", events_only}, {"dominant", dominant}, {"rates", rates_json}};
}

EventEstimate estimate_events(const sections::SharedParams& p, const pipelines::Pipeline& pipeline) {
  EventEstimate e;
  e.duration_s = p.duration_s;
  e.rates = pipelines::shared_event_rates(p);
  for (pipelines::EventRate& r : pipeline.event_rates(p)) e.rates.push_back(std::move(r));
  std::map<std::string, double> by_key;
  for (const pipelines::EventRate& r : e.rates) {
    const double n = r.per_s * e.duration_s;
    e.events += n;
    if (!r.steps) e.events_only += n;
    by_key[r.pointer] += n;
  }
  for (const auto& [pointer, n] : by_key)
    if (e.dominant.empty() || n > e.dominant_share) {
      e.dominant = pointer;
      e.dominant_share = n;
    }
  if (e.events > 0.0) e.dominant_share /= e.events;
  return e;
}

void check_event_budget(const EventEstimate& estimate, double max_events) {
  if (max_events <= 0.0 || estimate.events <= max_events) return;
  char duration[32];
  std::snprintf(duration, sizeof duration, "%.6g", estimate.duration_s);
  // What the dominant key drives: events, or steps of work done without them.
  bool steps = true;
  for (const pipelines::EventRate& r : estimate.rates)
    if (r.pointer == estimate.dominant && !r.steps) steps = false;
  throw scenario::ScenarioError(estimate.dominant, "about " + count_text(estimate.events, 1) +
                                                       (steps ? " steps of work over " : " events over ") + duration +
                                                       " s (limit " + count_text(max_events, 0) +
                                                       "; --max-events raises it)");
}

}  // namespace latsim::run
