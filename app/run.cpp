// latsim run: one scenario, its result files and its headline figures.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "latsim/des/stop_token.hpp"
#include "latsim/results/run_files.hpp"
#include "latsim/run/prepared_run.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"
#include "latsim/scenario/readable.hpp"
#include "latsim/sweep/claims.hpp"
#include "latsim/sweep/progress_line.hpp"
#include "latsim/sweep/store.hpp"
#include "stop_signals.hpp"

namespace latsim::app {

using namespace sweep;  // the progress line and the staging clean-up this command shares with sweeps

namespace {

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
  if (const auto rc = refuse_out_dir("latsim run", out_dir)) return *rc;
  remove_stale_staging(out_dir);
  const StopSignals& signals = StopSignals::installed();
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
    // Reading the files the scenario names (a capture of 256 MB takes
    // seconds) answers a signal too, not only the simulation.
    const des::ScopedStopFlag reading(&signals.flag());
    const auto doc = run::load_scenario(file, sets);
    // Built once, fully validated before the output directory is touched: bad input writes nothing.
    run::PreparedRun prepared(doc, opt);
    summary = prepared.run();
  } catch (const scenario::ScenarioError& e) {
    return bad_input(file, e);
  } catch (const des::StopRequested&) {
    shown.finish();
    if (StopSignals::first_word())
      std::fprintf(stderr, "%s: stopped by %s while reading its input; nothing written\n", name.c_str(),
                   signals.name());
    return signals.exit_code();
  } catch (const run::RunInterrupted& e) {
    shown.finish();
    if (StopSignals::first_word())
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

}  // namespace latsim::app
