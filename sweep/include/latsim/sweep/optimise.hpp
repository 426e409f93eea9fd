// Finding the best setting: minimise (or maximise) a figure over one
// pointer, subject to bounds on other figures, with common random numbers
// across evaluations (every evaluation runs the same seed and replications).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/scenario/schema.hpp"

namespace latsim::sweep {

/// A bound on a figure: "frames_missed<=2", "application_frame_rate_hz>=89.9".
struct FigureBound {
  std::string figure;  ///< dotted path, as find_figure reads it
  bool at_most = true;  ///< <=: at most `bound`; >=: at least
  double bound = 0;
};

/// Parses "FIGURE<=VALUE" or "FIGURE>=VALUE"; nullopt when malformed.
std::optional<FigureBound> parse_bound(const std::string& text);

/// How finely a key's values may be given, for a search over it: a frequency
/// given as a number to the micro-hertz (scenario::ConfigNode::rate_as_period
/// refuses more than 6 decimals), an integer to 1 (0 decimals); any other
/// key, or one not declared, takes any double (nullopt).
std::optional<int> setting_decimals(const scenario::KeySchema* key);

/// x rounded to `decimals` (the nearest multiple of 10^-decimals), kept in
/// [lo, hi] by taking the next multiple inward when the nearest lies outside;
/// x itself when decimals is nullopt; nullopt when no multiple lies in [lo, hi].
std::optional<double> setting_in_steps(double x, double lo, double hi, std::optional<int> decimals);

/// One point tried: the objective and how far it breaks the bounds.
struct Trial {
  double x = 0;
  double objective = 0;  ///< the figure to minimise (negated when maximising)
  double violation = 0;  ///< sum over bounds of how far each is exceeded; 0: feasible
  nlohmann::json figures = nlohmann::json::object();  ///< the objective and bound figures, as measured
};

/// Whether trial a is better than b: less violation first (a point that
/// breaks a bound is worse than any that keeps them), then a lower objective;
/// a tie keeps the lower x, so that the search is deterministic.
bool better(const Trial& a, const Trial& b);

/// Golden-section search of [lo, hi] for the best trial, to an interval of
/// at most `tolerance`. Exact for a merit (violation, objective) that is
/// unimodal over the interval (it falls, then rises); otherwise it finds a
/// local best. Evaluations: about log(hi - lo / tolerance) / log(1.618) + 2.
struct SearchResult {
  Trial best;
  std::vector<Trial> tried;  ///< in the order evaluated
};
SearchResult golden_section(const std::function<Trial(double)>& evaluate, double lo, double hi, double tolerance);

/// The largest n in [lo, hi] for which fits(n) holds, for a `fits` that holds
/// up to some n and not beyond (bisection); nullopt when fits(lo) fails.
std::optional<int64_t> largest_fitting(const std::function<bool(int64_t)>& fits, int64_t lo, int64_t hi);

/// "no figure F; this run reports A, B, C, ... (every figure: figures.json)":
/// the headline figures first, at most `max_names` names.
std::string missing_figure_message(const std::string& figure, const nlohmann::json& summary, size_t max_names = 8);

}  // namespace latsim::sweep
