// latsim compare: a capture (PresentMon, OVR Metrics Tool, VrApi, SteamVR
// frame timing) beside a run, read by latsim's one capture reader
// (sweep/compare.hpp); the CDF plots are drawn by analysis/compare.py from
// compare_values.json.
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "child_process.hpp"
#include "commands.hpp"
#include "stop_signals.hpp"
#include "latsim/capture/capture.hpp"
#include "latsim/des/stop_token.hpp"
#include "latsim/results/run_files.hpp"
#include "latsim/sweep/compare.hpp"
#include "latsim/scenario/readable.hpp"

namespace latsim::app {

int command_compare(int argc, char** argv) {
  CLI::App app{"Sets a capture beside a run, each quantity as its source defines it: count, mean, p50, p99 and the "
               "two-sample Kolmogorov-Smirnov distance, how the run stands to it (predicted, converted, derived, "
               "replayed, input, differs, no counterpart) and one verdict line (compare.md, compare.csv, "
               "compare_values.json), and overlaid CDFs (compare_<quantity>.png)",
               "latsim compare"};
  std::string capture, run, out, application;
  int64_t process_id = 0;
  double ks_threshold = 0.1, mean_tolerance = 0.1;
  bool no_plots = false;
  app.add_option("capture", capture,
                 "PresentMon CSV (current, v1 or v2 columns), OVR Metrics Tool CSV, VrApi logcat lines or SteamVR "
                 "Compositor_FrameTiming CSV")
      ->required();
  app.add_option("run", run, "run directory (presentmon.csv, figures.json, summary.json), or a PresentMon CSV")->required();
  auto* out_option = app.add_option("--out,-o", out, "output directory (default: RUN/compare, or beside a RUN file)");
  app.add_option("--application", application, "the capture's process, by Application (when it holds several)");
  app.add_option("--process-id", process_id, "the capture's process, by ProcessID (when it holds several)")
      ->check(CLI::Range(int64_t{1}, int64_t{1} << 40));
  app.add_option("--ks-threshold", ks_threshold, "samples agree at a KS distance at most this (default 0.1)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--mean-tolerance", mean_tolerance,
                 "a run total agrees within this share of the capture's mean (default 0.1)")
      ->check(CLI::Range(0.0, 10.0));
  app.add_flag("--no-plots", no_plots, "write the tables only");
  if (const auto rc = parse_options(app, argc, argv)) return *rc;
  // An --out given empty is a mistake, not the default.
  if (out_option->count() > 0)
    if (const auto rc = refuse_out_dir("latsim compare", out)) return *rc;
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(capture, ec)) {
    std::cerr << "compare: " << scenario::quote_value(capture) << ": not a regular file\n";
    return kExitBadInput;
  }
  if (!fs::is_directory(run, ec) && !fs::is_regular_file(run, ec)) {
    std::cerr << "compare: " << scenario::quote_value(run) << ": neither a run directory nor a capture file\n";
    return kExitBadInput;
  }
  const fs::path out_dir = !out.empty() ? fs::path(out)
                           : fs::is_directory(run, ec) ? fs::path(run) / "compare"
                                                       : fs::absolute(run).parent_path() / "compare";
  if (const auto rc = refuse_out_dir("latsim compare", out_dir.string())) return *rc;
  sweep::CompareRequest request{capture, run, {application, std::nullopt}, ks_threshold, mean_tolerance};
  if (process_id != 0) request.select.process_id = process_id;
  sweep::Comparison comparison;
  try {
    const des::ScopedStopFlag reading(&StopSignals::installed().flag());
    comparison = sweep::compare_capture(request);
  } catch (const des::StopRequested&) {
    if (StopSignals::first_word())
      std::cerr << "compare: stopped by " << StopSignals::installed().name() << " while reading; nothing written\n";
    return StopSignals::installed().exit_code();
  } catch (const capture::CaptureError& e) {
    std::cerr << scenario::readable(std::string("compare: ") + e.what()) << "\n";
    return kExitBadInput;
  } catch (const sweep::CompareError& e) {
    std::cerr << scenario::readable(std::string("compare: ") + e.what()) << "\n";
    return kExitBadInput;
  }
  for (const std::string& w : comparison.warnings) std::cerr << scenario::readable("compare: warning: " + w) << "\n";
  const bool made_here = !fs::exists(out_dir, ec);
  try {
    fs::create_directories(out_dir);
    results::write_file_atomically(out_dir / "compare.csv", sweep::compare_csv(comparison));
    results::write_file_atomically(out_dir / "compare_values.json", sweep::compare_values_json(comparison));
    results::write_file_atomically(out_dir / "compare.md", sweep::compare_markdown(comparison));
  } catch (const std::exception& e) {
    std::cerr << "compare: cannot write into " << out_dir.string() << ": " << e.what() << "\n";
    return kExitFailure;
  }
  if (!no_plots) {
    try {
      const ChildResult child = run_child({python_interpreter(), analysis_script("compare.py").string(), out_dir.string()});
      if (child.exit_code == 130 || child.exit_code == 143 || StopSignals::installed().requested()) {
        // Stopped while drawing (the script said so and took its plots back): the tables go too.
        for (const char* name : {"compare.csv", "compare_values.json", "compare.md"}) fs::remove(out_dir / name, ec);
        if (made_here) fs::remove(out_dir, ec);
        return child.exit_code == 130 || child.exit_code == 143 ? child.exit_code : StopSignals::installed().exit_code();
      }
      if (child.exit_code != kExitOk) {
        std::cerr << "compare: the plots could not be drawn (python3 with matplotlib is needed); the tables are written\n";
        return kExitFailure;
      }
    } catch (const std::exception& e) {
      std::cerr << "compare: " << e.what() << "\n";
      return kExitFailure;
    }
  }
  std::cout << "compare: wrote " << (out_dir / "compare.md").string() << "\n";
  return kExitOk;
}

}  // namespace latsim::app
