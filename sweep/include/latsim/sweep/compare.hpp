// latsim compare: a capture (PresentMon, or a runtime's own statistics) set
// beside a run, quantity by quantity, each side read as its source defines
// it; replayed quantities said and left out of the verdict, definitions that
// differ said and converted where they can be (docs/figures.md, "latsim compare").
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "latsim/capture/capture.hpp"
#include "latsim/capture/comparison.hpp"

namespace latsim::sweep {

/// How the run stands to a quantity of the capture.
enum class Standing {
  predicted,       ///< the run computes it by the same definition: compared, in the verdict
  converted,       ///< defined differently; converted to one definition, then compared, in the verdict
  derived,         ///< the run computes it from replayed values and its own model: compared, in the verdict
  replayed,        ///< the run plays the capture's own values back: shown, left out of the verdict
  input,           ///< set by the scenario (a display's refresh rate, a cost): shown, left out
  differs,         ///< defined differently and not convertible: shown, left out
  no_counterpart,  ///< one side has no such quantity: left out
};

/// "predicted", "converted", ... as the reports write it.
const char* standing_name(Standing s);

/// One side's values of a quantity.
struct CompareSide {
  std::string column;              ///< where it was read (a column, a figure, or how it was computed)
  std::vector<double> values;      ///< samples (a frame's, a second's); one value for a run total
  bool total_only = false;         ///< a single figure, not a sample of the quantity's distribution
  capture::SampleStats stats;
};

/// One quantity side by side.
struct CompareRow {
  std::string key;    ///< compare_<key>.png, the row's name in compare.csv
  std::string label;  ///< "frame interval (ms)"
  CompareSide capture, run;
  Standing standing = Standing::predicted;
  std::string note;                 ///< the definitions, and any conversion
  std::optional<double> ks;         ///< both sides samples: the KS distance
  std::optional<bool> agrees;       ///< in the verdict: whether it agrees
  std::string verdict;              ///< one line
};

/// What to compare, and the verdict's tolerances.
struct CompareRequest {
  std::filesystem::path capture;    ///< PresentMon CSV, OVR Metrics CSV, VrApi log, SteamVR frame timing CSV
  std::filesystem::path run;        ///< a run directory (presentmon.csv, figures.json, summary.json) or another capture
  capture::ProcessSelect select;    ///< the capture's process (PresentMon captures of several)
  double ks_threshold = 0.1;        ///< samples agree at a KS distance at most this
  double mean_tolerance = 0.1;      ///< a total agrees within this share of the capture's mean (or the floor)
};

/// The rows and what was read.
struct Comparison {
  std::string capture_text, run_text;  ///< what each side is (file, process, frames or seconds)
  std::vector<CompareRow> rows;
  std::vector<std::string> notes;      ///< about the two sides as a whole (displays, replayed files)
  /// Legal but doubtful: a capture with frames (or rows) and not one value
  /// of any timing quantity (every cell NA), one line each.
  std::vector<std::string> warnings;
};

/// Bad arguments or files: what() names the file (and line) and the reason.
class CompareError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads both sides and sets them side by side. Throws capture::CaptureError
/// or CompareError.
Comparison compare_capture(const CompareRequest& request);

/// compare.md, compare.csv and compare_values.json (each quantity's values
/// of each side, for the plots) of a comparison.
std::string compare_markdown(const Comparison& c);
std::string compare_csv(const Comparison& c);
std::string compare_values_json(const Comparison& c);

}  // namespace latsim::sweep
