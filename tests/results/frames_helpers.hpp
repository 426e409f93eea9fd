// Small scenarios for the frame capture and frameless tests, run in-process.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>

#include "latsim/des/random.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

namespace latsim::frames_test {

/// A 64 x 48 progressive 60 Hz display, still head, 1000 Hz tracker on a
/// direct link, instant double buffering; no scene (nothing is cast).
inline nlohmann::json small_scenario() {
  return {{"duration_s", 0.5},
          {"seed", 3},
          {"motion", {{"type", "still"}}},
          // Fixed clock phases: pinned images must not move with drawn ones.
          {"tracker", {{"rate_hz", 1000}, {"phase_ms", 0}}},
          {"display", {{"refresh_hz", 60}, {"width_px", 64}, {"height_px", 48}, {"hfov_deg", 60}, {"phase_ms", 0}}},
          {"pipeline", {{"type", "double_buffer"}, {"render", {{"fixed_ms", 0}}}}}};
}

/// Asks for frames of the test pattern.
inline void capture(nlohmann::json& scenario, nlohmann::json frames) {
  scenario["frames"] = std::move(frames);
  scenario["scene"] = {{"type", "test_pattern"}};
}

inline nlohmann::json frameless(const char* strategy) {
  return {{"type", "frameless"}, {"strategy", strategy}, {"full_images_per_s", 5}};
}

/// A fresh, empty directory under the system temporary directory.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("latsim_frames_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir;
}

/// Runs a scenario; with out_dir set, writes its result files there.
inline nlohmann::json run(const nlohmann::json& scenario, const std::filesystem::path& out_dir = {}) {
  run::RunOptions options;
  options.out_dir = out_dir;
  return run::run_scenario(scenario::ScenarioDocument::from_json(scenario, LATSIM_SOURCE_DIR "/scenarios"),
                                 options);
}

inline std::string file_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline uint64_t file_hash(const std::filesystem::path& file) { return des::fnv1a64(file_bytes(file)); }

inline const nlohmann::json& fig(const nlohmann::json& summary, const char* name) {
  return summary.at("figures").at(name);
}

}  // namespace latsim::frames_test
