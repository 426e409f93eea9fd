// Runs a scenario with the raw sample log and keeps what was recorded after
// a warm-up: steady-state figures, without the first frames a predictor
// makes before it has seen two samples or the pipeline has filled.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

namespace latsim::testing {

/// Named samples recorded at or after a time.
using SampleSeries = std::map<std::string, std::vector<double>>;

/// A run's summary and the samples it recorded after its warm-up.
struct SteadyRun {
  nlohmann::json summary;
  SampleSeries after;
};

inline SteadyRun steady_samples(const scenario::ScenarioDocument& doc, double after_ms) {
  static int calls = 0;
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("latsim_steady_" + std::to_string(::getpid()) + "_" + std::to_string(calls++));
  std::filesystem::remove_all(dir);
  run::RunOptions options;
  options.out_dir = dir;
  options.write_samples = true;
  SteadyRun run{run::run_scenario(doc, options), {}};
  SampleSeries& series = run.after;
  std::ifstream in(dir / "samples.csv");
  std::string line;
  std::getline(in, line);  // t_ms,name,value
  while (std::getline(in, line)) {
    const size_t a = line.find(','), b = line.find(',', a + 1);
    if (std::stod(line.substr(0, a)) < after_ms) continue;
    series[line.substr(a + 1, b - a - 1)].push_back(std::stod(line.substr(b + 1)));
  }
  std::filesystem::remove_all(dir);
  return run;
}

inline double mean_of(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

inline double max_of(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, x);
  return m;
}

}  // namespace latsim::testing
