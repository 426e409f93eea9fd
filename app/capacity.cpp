// latsim capacity: the largest count (of triangles, by default) whose
// missed-field fraction stays within a threshold, by bisection.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "latsim/results/run_files.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/sweep/optimise.hpp"
#include "latsim/sweep/run_table.hpp"
#include "latsim/scenario/readable.hpp"
#include "stop_signals.hpp"

namespace latsim::app {

namespace {

// A --metric the runs do not report: a bad command line, named with the figures they do report.
struct MissingMetric {
  std::string text;
};

}  // namespace

int command_capacity(int argc, char** argv) {
  CLI::App app{"Bisect for the largest triangle count whose missed-field fraction stays at or below a threshold",
               "latsim capacity"};
  std::string file, pointer = "/scene/triangles", metric = "missed_field_fraction", out_dir;
  std::vector<std::string> sets;
  int64_t lo = 0, hi = 100000;
  double threshold = 0.0;
  double max_events = run::kDefaultMaxEvents;
  app.add_option("scenario", file, "scenario JSON file")->required();
  app.add_option("--pointer", pointer, "the JSON pointer of the count to vary")->capture_default_str();
  app.add_option("--metric", metric, "figure that must stay at or below the threshold")->capture_default_str();
  app.add_option("--threshold", threshold, "largest acceptable value of the metric (0: no field missed)")
      ->check(non_negative_number())
      ->capture_default_str();
  app.add_option("--max", hi, "upper bound of the search")->capture_default_str();
  app.add_option("--out,-o", out_dir, "also write DIR/capacity.json (the result and every count tried)");
  app.add_option("--set", sets, "override a value: /json/pointer=value (repeatable)");
  add_max_events_option(app, max_events);
  if (const auto rc = parse_options(app, argc, argv)) return *rc;
  if (!out_dir.empty())
    if (const auto rc = refuse_out_dir("latsim capacity", out_dir)) return *rc;
  if (hi < lo) {
    std::fprintf(stderr, "latsim capacity: --max must be at least %lld, got %lld\n", static_cast<long long>(lo),
                 static_cast<long long>(hi));
    return kExitBadInput;
  }
  const StopSignals& signals = StopSignals::installed();
  const std::string name = scenario::readable(file, 2 * scenario::kQuotedChars);
  nlohmann::json tried = nlohmann::json::array();
  // Prints the result and, when asked, writes it with every count tried.
  auto finish = [&](int64_t max_count, const char* note) {
    std::printf("max_triangles_per_field=%lld%s\n", static_cast<long long>(max_count), note);
    if (out_dir.empty()) return;
    std::filesystem::create_directories(out_dir);
    const nlohmann::json doc{{"scenario", file},         {"pointer", pointer}, {"metric", metric},
                             {"threshold", threshold},   {"max_triangles_per_field", max_count},
                             {"note", note},             {"tried", tried},
                             {"command_line", command_line_of(argc, argv)}, {"latsim", run::latsim_version()},
                             {"git_revision", run::latsim_git_revision()}};
    results::write_file_atomically(std::filesystem::path(out_dir) / "capacity.json", doc.dump(2) + "\n");
  };
  try {
    // Whether the scenario with count n keeps the metric within the threshold.
    auto fits = [&](int64_t n) {
      std::vector<std::string> s = sets;
      s.push_back(pointer + "=" + std::to_string(n));
      run::RunOptions options;
      options.max_events = max_events;
      options.stop = &signals.flag();
      const auto summary = run::run_scenario(run::load_scenario(file, s), options);
      const auto& f = summary["figures"];
      // A fraction of no ended field judges nothing (it reads 0): a load at
      // which no field ends is over capacity, and a run in which not even
      // the scenario at the lower bound ends one is too short to judge.
      if (metric == "missed_field_fraction" && f.contains("frames_completed") && f.contains("missed_fields") &&
          f["frames_completed"].get<int64_t>() + f["missed_fields"].get<int64_t>() == 0) {
        if (n == lo)
          throw scenario::ScenarioError("/duration_s", "no field ended in the run at " + pointer + "=" +
                                                           std::to_string(n) + ", so capacity cannot be judged: "
                                                           "simulate longer");
        tried.push_back({{"count", n}, {"fields_ended", 0}});
        return false;
      }
      const std::optional<double> found = sweep::find_figure(summary, metric);
      if (!found) throw MissingMetric{sweep::missing_figure_message(metric, summary)};
      const double value = *found;
      tried.push_back({{"count", n}, {metric, value}});
      return value <= threshold;
    };
    // The bisection latsim optimise's constraints use (sweep::largest_fitting).
    const std::optional<int64_t> largest = sweep::largest_fitting(fits, lo, hi);
    if (!largest) finish(-1, " (over the threshold even with none)");
    else if (*largest == hi) finish(hi, " (within the threshold up to --max: raise it)");
    else finish(*largest, "");
  } catch (const MissingMetric& e) {
    std::fprintf(stderr, "%s: --metric %s: %s\n", name.c_str(), scenario::readable(metric, scenario::kQuotedChars).c_str(),
                 scenario::readable(e.text).c_str());
    return kExitBadInput;
  } catch (const run::RunInterrupted& e) {
    if (StopSignals::first_word())
      std::fprintf(stderr, "latsim capacity: stopped by %s after %zu count(s): %s; nothing written\n",
                   signals.name(), tried.size(), e.what());
    return signals.exit_code();
  } catch (const scenario::ScenarioError& e) {
    return bad_input(file, e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name.c_str(), scenario::readable(e.what()).c_str());
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace latsim::app
