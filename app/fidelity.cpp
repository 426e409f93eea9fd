// latsim fidelity: what one step of a fidelity knob changes in a figure and
// what it costs in wall time, events and memory.
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "child_process.hpp"
#include "commands.hpp"
#include "latsim/results/run_files.hpp"
#include "latsim/run/event_budget.hpp"
#include "latsim/run/prepared_run.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/sweep/fidelity_table.hpp"
#include "latsim/sweep/run_table.hpp"
#include "latsim/io/temporaries.hpp"
#include "latsim/scenario/readable.hpp"
#include "stop_signals.hpp"

namespace latsim::app {

using namespace sweep;  // the sweep engine this command drives

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

/// What `latsim fidelity` was asked to do.
struct FidelityRequest {
  std::string scenario_file;
  std::string vary;
  std::string metric;
  std::string out_dir = "out/fidelity";
  std::vector<std::string> sets;
  std::optional<uint64_t> seed;
  double max_events = run::kDefaultMaxEvents;  ///< --max-events, for every level
  bool progress = false;                        ///< --progress: each level's runs show theirs, terminal or not
};

// A few figure names a metric could be, for the one-line error when it is not found.
std::string some_figure_names(const Json& summary) {
  const FlatFigures flat = flatten_figures(summary.value("figures", Json::object()));
  std::vector<std::string> names;
  if (find_figure(summary, "motion_to_photon_ms.mean")) names.push_back("motion_to_photon_ms.mean");
  std::string last;
  for (const auto& s : flat.stats) {
    if (s.name == last) continue;
    last = s.name;
    if (s.name != "motion_to_photon_ms" && names.size() < 3) names.push_back(s.name + ".mean");
  }
  for (const auto& f : flat.scalars)
    if (names.size() < 5) names.push_back(f.name);
  std::string text;
  for (const auto& n : names) text += (text.empty() ? "" : ", ") + n;
  return text;
}

// A stop request seen between levels or in one: the command says so and
// ends, in one line: the level's run, stopped with it, has said it already.
struct Stopped {
  bool child_said_so = false;
};

// One line on stderr, however long or strange what it quotes.
void say(const std::string& text) { std::cerr << scenario::readable("fidelity: " + text) << "\n"; }

// Runs one level in its own process, so its peak memory is its own.
FidelityLevel run_level(const FidelityRequest& request, const std::string& assignment, const std::string& value,
                        const fs::path& level_dir) {
  std::vector<std::string> argv{self_executable().string(), "run", request.scenario_file, "--out", level_dir.string(),
                                "--quiet", "--set", assignment};
  for (const auto& s : request.sets) argv.insert(argv.end(), {"--set", s});
  if (request.seed) argv.insert(argv.end(), {"--seed", std::to_string(*request.seed)});
  char max_events[32];
  std::snprintf(max_events, sizeof max_events, "%.17g", request.max_events);
  argv.insert(argv.end(), {"--max-events", max_events});
  if (request.progress) argv.push_back("--progress");
  const ChildResult child = run_child(argv);
  if (StopSignals::installed().requested())
    throw Stopped{child.exit_code == 128 + SIGINT || child.exit_code == 128 + SIGTERM};
  if (child.exit_code != 0)
    throw std::runtime_error("the run at " + assignment + " failed with exit status " + std::to_string(child.exit_code));
  const std::optional<Json> summary_read = results::read_summary(level_dir / "summary.json", "run the level again");
  if (!summary_read) throw std::runtime_error("the run at " + assignment + " wrote no summary.json");
  const Json& summary = *summary_read;
  const auto metric = find_figure(summary, request.metric);
  if (!metric) throw std::runtime_error("the run at " + assignment + " has no figure " + request.metric);
  FidelityLevel level;
  level.value = value;
  level.metric = *metric;
  level.wall_s = summary.value("wall_s", child.wall_s);
  level.events = summary.value("events", uint64_t{0});
  level.peak_rss_mb = child.peak_rss_mb;
  return level;
}

int plot(const fs::path& out_dir) {
  const ChildResult child =
      run_child({python_interpreter(), analysis_script("fidelity_plot.py").string(), out_dir.string()});
  return child.exit_code;
}

}  // namespace

int command_fidelity(int argc, char** argv) {
  CLI::App app{"Runs a scenario at each level of a fidelity knob and tabulates a metric's error against the finest "
               "level (the last value) together with wall time, events and peak memory",
               "latsim fidelity"};
  FidelityRequest request;
  uint64_t seed = 0;
  app.add_option("scenario", request.scenario_file, "scenario JSON file")->required();
  app.add_option("--vary", request.vary, "the knob and its levels, coarsest first: /json/pointer=v1,v2,...")->required();
  app.add_option("--metric", request.metric, "a figure such as motion_to_photon_ms.mean, or a dotted summary path")
      ->required();
  app.add_option("--out,-o", request.out_dir, "output directory")->capture_default_str();
  app.add_option("--set", request.sets, "override a value for every level: /json/pointer=value (repeatable)");
  auto* seed_option = app.add_option("--seed", seed, "run seed (overrides the scenario's /seed)");
  add_max_events_option(app, request.max_events);
  app.add_flag("--progress", request.progress,
               "each level's run reports its progress, also when stderr is not a terminal (on a terminal a level "
               "longer than a few seconds always does)");
  if (const auto rc = parse_options(app, argc, argv)) return *rc;
  if (*seed_option) request.seed = seed;

  FidelityAxis axis;
  try {
    axis = parse_vary(request.vary);
  } catch (const std::invalid_argument& e) {
    say(e.what());
    return kExitBadInput;
  }
  if (const auto rc = refuse_out_dir("latsim fidelity", request.out_dir)) return *rc;
  const StopSignals& signals = StopSignals::installed();
  // Every level must be a valid scenario before anything runs or is written;
  // each one's expected events (declared rates x duration) price it.
  // The coarsest level is also run in memory below, from the same build.
  std::vector<double> expected_events;
  std::optional<scenario::ScenarioDocument> coarsest_doc;
  std::unique_ptr<run::PreparedRun> coarsest;
  for (const auto& value : axis.values) {
    std::vector<std::string> overrides = request.sets;
    overrides.push_back(axis.pointer + "=" + value);
    try {
      if (!coarsest) {
        coarsest_doc.emplace(run::load_scenario(request.scenario_file, overrides));
        run::RunOptions in_memory;
        in_memory.stop = &signals.flag();
        in_memory.seed = request.seed;
        in_memory.max_events = request.max_events;
        coarsest = std::make_unique<run::PreparedRun>(*coarsest_doc, in_memory);
        expected_events.push_back(coarsest->estimate().events);
        continue;
      }
      expected_events.push_back(
          run::estimate_scenario_events(run::load_scenario(request.scenario_file, overrides), request.max_events));
    } catch (const scenario::ScenarioError& e) {
      const std::string at = scenario::readable_pointer(axis.pointer) + "=" + scenario::quote_value(value);
      std::cerr << scenario::readable(e.line(request.scenario_file) + " (at " + at + ")") << "\n";
      return kExitBadInput;
    }
  }

  // The metric must be a figure of the scenario before anything is written:
  // the coarsest level, run in memory (no files), says which figures it has.
  try {
    const Json summary = coarsest->run();
    if (!find_figure(summary, request.metric)) {
      std::cerr << scenario::readable(request.scenario_file, 2 * scenario::kQuotedChars) << ": --metric "
                << scenario::quote_value(request.metric) << " is not a figure of it (it has "
                << some_figure_names(summary) << ", ...; every one is in a run's figures.json)\n";
      return kExitBadInput;
    }
    // The cost before it is paid: each level's expected events at the pace the
    // coarsest level just ran.
    const double pace_s = expected_events.front() > 0 ? summary.value("wall_s", 0.0) / expected_events.front() : 0.0;
    double total_s = 0;
    std::string levels_text;
    for (size_t i = 0; i < axis.values.size(); ++i) {
      total_s += pace_s * expected_events[i];
      levels_text += (i ? ", " : "") + axis.values[i] + " " + run::count_text(expected_events[i], 1);
    }
    std::fprintf(stderr, "fidelity: %zu levels, expected events %s; at the first level's pace about %.3g s in all\n",
                 axis.values.size(), levels_text.c_str(), total_s);
  } catch (const run::RunInterrupted& e) {
    if (StopSignals::first_word())
      say(std::string("stopped by ") + signals.name() + ": " + e.what() + "; nothing written");
    return signals.exit_code();
  } catch (const std::exception& e) {
    say(e.what());
    return kExitFailure;
  }

  const fs::path out_dir = request.out_dir;
  // A directory this command makes is removed whole when it is stopped (the
  // watchdog's deadline included): an unfinished table leaves nothing.
  std::error_code ec;
  const bool made_here = !fs::exists(out_dir, ec);
  const fs::path made = made_here ? out_dir : out_dir / "levels";
  const bool owned = made_here || !fs::exists(made, ec);
  if (owned) io::register_temporary(made);
  std::vector<FidelityLevel> levels;
  try {
    fs::create_directories(out_dir / "levels");
    for (size_t i = 0; i < axis.values.size(); ++i) {
      const fs::path level_dir = out_dir / "levels" / level_dir_name(i, axis.values[i]);
      levels.push_back(run_level(request, axis.pointer + "=" + axis.values[i], axis.values[i], level_dir));
      std::fprintf(stderr, "fidelity: %s=%s: %s = %.6g, %llu events, %.3f s\n", axis.pointer.c_str(),
                   axis.values[i].c_str(), request.metric.c_str(), levels.back().metric,
                   static_cast<unsigned long long>(levels.back().events), levels.back().wall_s);
    }
  } catch (const Stopped& stopped) {
    if (owned) fs::remove_all(made, ec);
    io::unregister_temporary(made);
    if (!stopped.child_said_so && StopSignals::first_word())
      say(std::string("stopped by ") + signals.name() + " after " + std::to_string(levels.size()) + " of " +
          std::to_string(axis.values.size()) + " level(s); nothing written");
    return signals.exit_code();
  } catch (const std::invalid_argument& e) {
    say(e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    say(e.what());
    return kExitFailure;
  }
  io::unregister_temporary(made);
  compute_errors(levels);
  const std::string markdown = fidelity_markdown(axis, request.metric, levels);
  std::fputs(markdown.c_str(), stdout);
  try {
    results::write_file_atomically(out_dir / "fidelity.csv", fidelity_csv(axis, request.metric, levels));
    results::write_file_atomically(out_dir / "fidelity.md", markdown);
    const int plotted = plot(out_dir);
    if (signals.requested()) {
      if (StopSignals::first_word())
        say(std::string("stopped by ") + signals.name() + " while drawing the plot; the tables are written");
      return signals.exit_code();
    }
    if (plotted != 0) {
      std::cerr << "fidelity: the plot could not be drawn (python3 with matplotlib is needed); the tables are written\n";
      return kExitFailure;
    }
  } catch (const std::exception& e) {
    std::cerr << "fidelity: " << e.what() << "\n";
    return kExitFailure;
  }
  std::fflush(stdout);
  std::fprintf(stderr, "fidelity: wrote %s, fidelity.md and fidelity.png/svg\n", (out_dir / "fidelity.csv").c_str());
  return kExitOk;
}

}  // namespace latsim::app
