// The keys of a sweep file, declared as scenario keys are (scenario::Section),
// so that a sweep file is read by the same machinery: a wrong type, a value
// out of range, a missing or unknown key is reported in the same words, at
// its JSON pointer.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/scenario/section.hpp"

namespace latsim::sweep {

/// One entry of "axes" as written.
struct SweepFileAxis {
  std::string pointer;
  nlohmann::json values;  ///< null when absent
  nlohmann::json range;   ///< {"from", "to", "step"}; null when absent
  std::string label;
};

/// A sweep file as written, every key read and checked for its type and range.
struct SweepFile {
  enum class Mode { cartesian, zip };
  std::string description;
  std::string base;
  std::vector<SweepFileAxis> axes;
  Mode mode = Mode::cartesian;
  int64_t replications = 1;
  nlohmann::json seed;  ///< null when absent: the base scenario's
  nlohmann::json overrides = nlohmann::json::object();
  std::string keep;     ///< empty when absent
  std::vector<std::string> figures;
};

/// Declares (or reads) every key of a sweep file.
void bind(scenario::Section& s, SweepFile& f);

/// Reads a sweep file's JSON; throws SweepError naming `file` and the pointer.
SweepFile read_sweep_file(const nlohmann::json& sweep, const std::filesystem::path& file);

}  // namespace latsim::sweep
