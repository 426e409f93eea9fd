// latsim run / validate / capacity / schema.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "latsim/results/run_files.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/sweep/progress_line.hpp"
#include "stop_signals.hpp"
#include "latsim/sweep/claims.hpp"
#include "latsim/sweep/common.hpp"
#include "latsim/sweep/optimise.hpp"
#include "latsim/sweep/run_table.hpp"
#include "latsim/sweep/store.hpp"

namespace latsim::app {

using namespace sweep;  // the sweep engine this command drives

namespace {

std::vector<std::string> command_line_of(int argc, char** argv) {
  std::vector<std::string> out{"latsim"};
  for (int i = 0; i < argc; ++i) out.emplace_back(argv[i]);
  return out;
}

// One line on stderr: the file, the JSON pointer and what is wrong.
int bad_input(const std::string& file, const scenario::ScenarioError& e) {
  std::fprintf(stderr, "%s\n", e.line(file).c_str());
  return kExitBadInput;
}

// Legal but doubtful input, one line each on stderr.
void print_warnings(const std::string& file, const std::vector<std::string>& warnings) {
  const std::string name = scenario::readable(file, 2 * scenario::kQuotedChars);
  for (const auto& w : warnings) std::fprintf(stderr, "%s: warning: %s\n", name.c_str(), scenario::readable(w).c_str());
}

// What is wrong with --out before anything runs, if anything.
std::optional<std::string> output_dir_problem(const std::string& out_dir) {
  if (out_dir.empty()) return "must name a directory";
  std::error_code ec;
  const auto st = std::filesystem::status(out_dir, ec);
  if (std::filesystem::exists(st) && !std::filesystem::is_directory(st))
    return scenario::quote_value(out_dir) + " exists and is not a directory";
  return std::nullopt;
}

// Removes what runs into the same directory left when they were killed:
// staging directories "<out>.tmp.<pid>" of processes that are gone.
void remove_stale_staging(const std::string& out_dir) {
  namespace fs = std::filesystem;
  const fs::path mine = results::staging_dir_of(out_dir, 0);
  const std::string prefix = mine.filename().string().substr(0, mine.filename().string().size() - 1);
  std::error_code ec;
  for (fs::directory_iterator it(mine.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0 || !is_temporary_name(name)) continue;
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    std::error_code rm;
    if (pid > 0 && !process_alive(pid, 0)) fs::remove_all(it->path(), rm);
  }
}

}  // namespace

int command_run(int argc, char** argv) {
  CLI::App app{"Run one scenario and write its results (summary.json, figures.json, timeline, ledger, samples)",
               "latsim run"};
  std::string file, out_dir = "out/run";
  std::vector<std::string> sets;
  uint64_t seed = 0;
  uint64_t replication = 0;
  bool samples = false, ledger = false, quiet = false, progress = false, profile = false, no_presentmon = false;
  double max_events = run::kDefaultMaxEvents;
  app.add_option("scenario", file, "scenario JSON file")->required();
  app.add_option("--out,-o", out_dir, "output directory")->capture_default_str();
  auto* seed_opt = app.add_option("--seed", seed, "run seed (overrides the scenario's /seed)");
  app.add_option("--replication", replication, "replication index (independent random streams)");
  app.add_option("--set", sets, "override a value: /json/pointer=value (repeatable)");
  app.add_flag("--samples", samples, "also write samples.csv (every recorded sample)");
  app.add_flag("--ledger", ledger, "also write frames.csv (every stage timestamp of every frame)");
  app.add_flag("--no-presentmon", no_presentmon,
               "do not write presentmon.csv (the application's frames as a PresentMon capture)");
  app.add_flag("--profile", profile, "also measure wall time per model (summary.json models.*.wall_s)");
  app.add_flag("--quiet,-q", quiet, "print nothing on success");
  app.add_flag("--progress", progress,
               "report progress from the start, also when stderr is not a terminal (on a terminal a run "
               "longer than a few seconds always shows it)");
  add_max_events_option(app, max_events);
  if (const auto rc = parse_options(app, argc, argv)) return *rc;
  if (const auto problem = output_dir_problem(out_dir)) {
    std::fprintf(stderr, "latsim run: --out %s\n", problem->c_str());
    return kExitBadInput;
  }
  remove_stale_staging(out_dir);
  StopSignals signals;
  SimulationProgress shown(progress);
  run::RunOptions opt;
  opt.command_start = std::chrono::steady_clock::now();
  if (*seed_opt) opt.seed = seed;
  opt.replication = replication;
  opt.out_dir = out_dir;
  opt.write_samples = samples;
  opt.write_ledger = ledger;
  opt.write_presentmon = !no_presentmon;
  opt.profile = profile;
  opt.max_events = max_events;
  opt.command_line = command_line_of(argc, argv);
  opt.stop = &signals.flag();
  opt.progress = [&shown](const run::RunProgress& p) { shown.update(p); };
  nlohmann::json summary;
  const std::string name = scenario::readable(file, 2 * scenario::kQuotedChars);
  try {
    const auto doc = run::load_scenario(file, sets);
    // Validate fully before touching the output directory: bad input writes nothing.
    run::validate_scenario(doc, max_events);
    summary = run::run_scenario(doc, opt);
  } catch (const scenario::ScenarioError& e) {
    return bad_input(file, e);
  } catch (const run::RunInterrupted& e) {
    shown.finish();
    std::fprintf(stderr, "%s: stopped by %s: %s; nothing written\n", name.c_str(), signals.name(), e.what());
    return signals.exit_code();
  } catch (const std::exception& e) {
    // RunFailure names the model and the simulated time; WriteError the file and the reason.
    shown.finish();
    std::fprintf(stderr, "%s: %s; nothing written\n", name.c_str(), scenario::readable(e.what()).c_str());
    return kExitFailure;
  }
  shown.finish();
  if (!quiet) {
    const auto& f = summary["figures"];
    std::printf("%s -> %s/summary.json\n", name.c_str(), scenario::readable(out_dir).c_str());
    // The pipeline's headline figures, in its order (summary.json "headline").
    for (const auto& name : summary.value("headline", nlohmann::json::array())) {
      const auto& m = f[name.get<std::string>()];
      if (m.is_object() && m.contains("mean"))
        std::printf("  %s: mean %.3f  p50 %.3f  p99 %.3f  max %.3f  (%llu samples)\n", name.get<std::string>().c_str(),
                    m["mean"].get<double>(), m["p50"].get<double>(), m["p99"].get<double>(), m["max"].get<double>(),
                    static_cast<unsigned long long>(m["count"].get<uint64_t>()));
      else if (m.is_number_integer())
        std::printf("  %s: %lld\n", name.get<std::string>().c_str(), static_cast<long long>(m.get<int64_t>()));
      else if (m.is_number())
        std::printf("  %s: %.3f\n", name.get<std::string>().c_str(), m.get<double>());
    }
    std::printf("  events %llu, simulation loop %.3f s, whole run %.3f s, peak memory %.1f MB\n",
                static_cast<unsigned long long>(summary["events"].get<uint64_t>()), summary["wall_s"].get<double>(),
                summary["command_wall_s"].get<double>(), summary["peak_rss_mb"].get<double>());
  }
  print_warnings(file, summary["warnings"].get<std::vector<std::string>>());
  return kExitOk;
}

int command_validate(int argc, char** argv) {
  CLI::App app{"Check scenario and sweep files without running them", "latsim validate"};
  std::vector<std::string> files;
  std::vector<std::string> sets;
  bool resolved = false;
  double max_events = run::kDefaultMaxEvents;
  app.add_option("files", files, "scenario or sweep JSON files")->required();
  app.add_option("--set", sets, "override a value: /json/pointer=value (repeatable; scenarios only)");
  app.add_flag("--resolved", resolved, "print each scenario as it would run (every default applied) instead of ok");
  add_max_events_option(app, max_events);
  if (const auto rc = parse_options(app, argc, argv)) return *rc;
  int rc = kExitOk;
  for (const auto& file : files) {
    const std::string name = scenario::readable(file, 2 * scenario::kQuotedChars);
    try {
      if (is_sweep_file(file)) {
        rc = std::max(rc, validate_sweep(file, max_events));
        continue;
      }
      const auto doc = run::load_scenario(file, sets);
      print_warnings(file, run::validate_scenario(doc, max_events));
      if (resolved) std::printf("%s\n", doc.resolved().dump(2, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
      else std::printf("%s: ok\n", name.c_str());
    } catch (const scenario::ScenarioError& e) {
      rc = bad_input(file, e);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", name.c_str(), scenario::readable(e.what()).c_str());
      rc = kExitBadInput;
    }
  }
  return rc;
}

// A --metric the runs do not report: a bad command line, named with the figures they do report.
struct MissingMetric {
  std::string text;
};

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
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--max", hi, "upper bound of the search")->capture_default_str();
  app.add_option("--out,-o", out_dir, "also write DIR/capacity.json (the result and every count tried)");
  app.add_option("--set", sets, "override a value: /json/pointer=value (repeatable)");
  add_max_events_option(app, max_events);
  if (const auto rc = parse_options(app, argc, argv)) return *rc;
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
    std::fprintf(stderr, "latsim capacity: --metric %s: %s\n", metric.c_str(), e.text.c_str());
    return kExitBadInput;
  } catch (const scenario::ScenarioError& e) {
    return bad_input(file, e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", file.c_str(), e.what());
    return kExitFailure;
  }
  return kExitOk;
}

int command_schema(int argc, char** argv) {
  CLI::App app{"Print every scenario key with its type, default, range, unit and meaning", "latsim schema"};
  std::string format = "json-schema";
  app.add_option("--format", format, "json-schema (for editors and validators) or markdown (the reference)")
      ->check(CLI::IsMember({"json-schema", "markdown"}))
      ->capture_default_str();
  if (const auto rc = parse_options(app, argc, argv)) return *rc;
  const scenario::ObjectSchema schema = run::scenario_schema();
  if (format == "markdown") std::fputs(scenario::markdown_reference(schema).c_str(), stdout);
  else std::printf("%s\n", scenario::json_schema(schema).dump(2).c_str());
  return kExitOk;
}

}  // namespace latsim::app
