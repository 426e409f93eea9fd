// The run side of latsim compare: a run directory's presentmon.csv,
// figures.json and summary.json (which columns of which capture it replays).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/capture/presentmon.hpp"

namespace latsim::sweep {

/// What a run is and what it wrote.
struct RunSide {
  std::filesystem::path dir;
  std::optional<capture::PresentMonProcess> frames;  ///< presentmon.csv, when written
  nlohmann::json figures;                            ///< figures.json's "figures"
  std::string pipeline;                              ///< the resolved /pipeline/type
  double refresh_hz = 0.0;                           ///< the resolved /display/refresh_hz
  double seconds = 0.0;                              ///< simulated seconds the figures cover
  /// A column the run plays back from a capture (summary.json "captures").
  struct Replayed {
    std::filesystem::path file;
    std::string column, quantity;
    std::string application;
    std::optional<int64_t> process_id;
  };
  std::vector<Replayed> replayed;

  /// A figure's number (a distribution's `stat`), if the run has it.
  std::optional<double> figure(const std::string& name, const char* stat = nullptr) const;
};

/// Reads a run directory (throws CompareError naming what is missing).
RunSide read_run(const std::filesystem::path& dir);

/// latsim's name for what a replayed column holds ("cpu_busy", "gpu_busy",
/// "cpu_wait", "app_gpu", "timewarp_gpu"), or empty.
std::string replayed_quantity(const std::string& column);

/// Whether the run replays `quantity` of `file` (the same file, and the same
/// process when the entry names one).
bool replays(const RunSide& run, const std::filesystem::path& file, const std::string& quantity,
             const std::string& application, std::optional<int64_t> process_id);

}  // namespace latsim::sweep
