// latsim optimise: the setting of one pointer that minimises (or maximises)
// a figure, subject to bounds on other figures, by golden-section search with
// common random numbers (every evaluation runs the same seed and
// replications, so two settings differ only by the setting).
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "latsim/results/run_files.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/sweep/optimise.hpp"
#include "latsim/sweep/run_table.hpp"
#include "stop_signals.hpp"

namespace latsim::app {

namespace {

using Json = nlohmann::json;

struct Range {
  std::string pointer;
  double lo = 0, hi = 0;
};

// "/pointer=LO:HI"; nullopt when malformed.
std::optional<Range> parse_range(const std::string& text) {
  const size_t eq = text.rfind('=');
  const size_t colon = text.find(':', eq == std::string::npos ? 0 : eq);
  if (eq == std::string::npos || eq == 0 || text[0] != '/' || colon == std::string::npos) return std::nullopt;
  Range r;
  r.pointer = text.substr(0, eq);
  const std::string lo = text.substr(eq + 1, colon - eq - 1), hi = text.substr(colon + 1);
  char* end = nullptr;
  r.lo = std::strtod(lo.c_str(), &end);
  if (lo.empty() || end != lo.c_str() + lo.size()) return std::nullopt;
  r.hi = std::strtod(hi.c_str(), &end);
  if (hi.empty() || end != hi.c_str() + hi.size() || !(r.hi > r.lo)) return std::nullopt;
  if (!std::isfinite(r.lo) || !std::isfinite(r.hi) || !std::isfinite(r.hi - r.lo)) return std::nullopt;
  return r;
}

// A figure the runs do not report: a bad option, found at the first run.
struct MissingFigure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

int usage_error(const std::string& text) {
  std::fprintf(stderr, "latsim optimise: %s\n", scenario::readable(text).c_str());
  return kExitBadInput;
}

// The finest tolerance a search may ask for: a billionth of the interval or
// of the values in it. The golden section keeps 0.618 of the interval a
// step, so even this one ends after ln(1e9)/ln(1.618) = 44 steps (48
// settings with the first two probes and the ends); a finer one asks for
// differences double precision cannot hold near the values, and the search
// would never narrow to it.
double finest_tolerance(const Range& r) {
  return std::max({r.hi - r.lo, std::fabs(r.lo), std::fabs(r.hi)}) / 1e9;
}

}  // namespace

int command_optimise(int argc, char** argv) {
  CLI::App app{"Find the value of one pointer that minimises (or maximises) a figure within bounds on others, by "
               "golden-section search with common random numbers",
               "latsim optimise"};
  std::string file, vary, minimise, maximise, out_dir;
  std::vector<std::string> constraints, sets;
  double tolerance = 0;
  int replications = 1;
  app.add_option("scenario", file, "scenario JSON file")->required();
  app.add_option("--vary", vary, "/json/pointer=LO:HI: the setting searched, and its interval")->required();
  app.add_option("--minimise", minimise, "figure to minimise (dotted path; a distribution means its mean), e.g. "
                                         "rotation_latency_ms.p99");
  app.add_option("--maximise", maximise, "figure to maximise instead");
  app.add_option("--constraint", constraints, "FIGURE<=VALUE or FIGURE>=VALUE (repeatable), e.g. frames_missed<=2");
  auto* tolerance_option = app.add_option(
      "--tolerance", tolerance,
      "width of the final interval, in the pointer's unit (default: 1/1000 of it; at least 1e-9 of the interval and "
      "of its ends)");
  app.add_option("--replications", replications, "replications per setting (0..N-1, the same for every setting)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("--set", sets, "override a value: /json/pointer=value (repeatable)");
  app.add_option("--out,-o", out_dir, "also write DIR/optimise.json (the best setting and every setting tried)");
  if (const auto rc = parse_options(app, argc, argv)) return *rc;

  const auto range = parse_range(vary);
  if (!range) return usage_error("--vary " + scenario::quote_value(vary) + ": expected /json/pointer=LO:HI with finite LO < HI");
  if (minimise.empty() == maximise.empty()) return usage_error("give exactly one of --minimise and --maximise");
  const std::string objective = minimise.empty() ? maximise : minimise;
  std::vector<sweep::FigureBound> bounds;
  for (const std::string& c : constraints) {
    const auto b = sweep::parse_bound(c);
    if (!b) return usage_error("--constraint " + scenario::quote_value(c) + ": expected FIGURE<=VALUE or FIGURE>=VALUE");
    bounds.push_back(*b);
  }
  if (tolerance_option->count() == 0) tolerance = std::max((range->hi - range->lo) / 1000, finest_tolerance(*range));
  if (!(tolerance >= finest_tolerance(*range)) || !std::isfinite(tolerance))
    return usage_error("--tolerance must be a finite number of at least " + scenario::number_text(finest_tolerance(*range)) +
                       " (1e-9 of the interval and of its ends), got " + scenario::number_text(tolerance));
  // A setting goes into the scenario as the key accepts it: a frequency to
  // the micro-hertz, an integer whole; the search's interval must hold one.
  const auto decimals = sweep::setting_decimals(run::scenario_schema().key_at(range->pointer));
  if (!sweep::setting_in_steps(range->lo, range->lo, range->hi, decimals))
    return usage_error("--vary " + scenario::quote_value(vary) + ": " + range->pointer + " takes values in steps of " +
                       (*decimals == 0 ? std::string("1") : "1e-" + std::to_string(*decimals)) +
                       ", and none lies in the interval");
  if (!out_dir.empty())
    if (const auto rc = refuse_out_dir("latsim optimise", out_dir)) return *rc;
  const StopSignals& signals = StopSignals::installed();

  Json tried = Json::array();
  try {
    // Checks every key (the pointer included) before the first run.
    run::validate_scenario(run::load_scenario(file, sets));
    auto evaluate = [&](double probe) {
      const double x = *sweep::setting_in_steps(probe, range->lo, range->hi, decimals);
      std::vector<std::string> s = sets;
      s.push_back(range->pointer + "=" + scenario::number_text(x));
      const scenario::ScenarioDocument doc = run::load_scenario(file, s);
      sweep::Trial t;
      t.x = x;
      std::vector<double> sums(1 + bounds.size(), 0.0);
      for (int r = 0; r < replications; ++r) {
        run::RunOptions options;
        options.replication = static_cast<uint64_t>(r);
        options.stop = &signals.flag();
        const Json summary = run::run_scenario(doc, options);
        for (size_t i = 0; i <= bounds.size(); ++i) {
          const std::string& figure = i == 0 ? objective : bounds[i - 1].figure;
          const auto v = sweep::find_figure(summary, figure);
          if (!v) throw MissingFigure(sweep::missing_figure_message(figure, summary));
          sums[i] += *v;
        }
      }
      const double n = replications;
      t.objective = (minimise.empty() ? -1.0 : 1.0) * sums[0] / n;
      t.figures[objective] = sums[0] / n;
      for (size_t i = 0; i < bounds.size(); ++i) {
        const double v = sums[i + 1] / n;
        t.figures[bounds[i].figure] = v;
        t.violation += std::max(0.0, bounds[i].at_most ? v - bounds[i].bound : bounds[i].bound - v);
      }
      tried.push_back({{"value", x}, {"figures", t.figures}, {"feasible", t.violation == 0}});
      return t;
    };
    const sweep::SearchResult result = sweep::golden_section(evaluate, range->lo, range->hi, tolerance);
    const sweep::Trial& best = result.best;
    std::printf("%s=%s: %s %s (%zu settings of %d replication%s, tolerance %s)%s\n", range->pointer.c_str(),
                scenario::number_text(best.x).c_str(), objective.c_str(),
                scenario::number_text(best.figures[objective].get<double>()).c_str(), result.tried.size(), replications,
                replications == 1 ? "" : "s", scenario::number_text(tolerance).c_str(),
                best.violation > 0 ? "; no setting kept every constraint: this one breaks them least" : "");
    if (!out_dir.empty()) {
      std::filesystem::create_directories(out_dir);
      const Json doc{{"scenario", file},
                     {"pointer", range->pointer},
                     {"interval", {range->lo, range->hi}},
                     {"objective", objective},
                     {"direction", minimise.empty() ? "maximise" : "minimise"},
                     {"constraints", constraints},
                     {"tolerance", tolerance},
                     {"replications", replications},
                     {"method", "golden-section search on (constraint violation, objective), common random numbers"},
                     {"best", {{"value", best.x}, {"figures", best.figures}, {"feasible", best.violation == 0}}},
                     {"tried", tried},
                     {"latsim", run::latsim_version()},
                     {"git_revision", run::latsim_git_revision()}};
      results::write_file_atomically(std::filesystem::path(out_dir) / "optimise.json", doc.dump(2) + "\n");
    }
  } catch (const scenario::ScenarioError& e) {
    std::fprintf(stderr, "%s\n", e.line(file).c_str());
    return kExitBadInput;
  } catch (const MissingFigure& e) {
    return usage_error(e.what());
  } catch (const run::RunInterrupted& e) {
    if (StopSignals::first_word())
      std::fprintf(stderr, "latsim optimise: stopped by %s after %zu setting(s): %s; nothing written\n",
                   signals.name(), tried.size(), e.what());
    return signals.exit_code();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", scenario::readable(file, 2 * scenario::kQuotedChars).c_str(),
                 scenario::readable(e.what()).c_str());
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace latsim::app
