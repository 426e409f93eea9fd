// Fuzz target: a runtime's statistics file (OVR Metrics Tool CSV, VrApi
// logcat lines, SteamVR Compositor_FrameTiming CSV) as read_runtime_stats
// reads it. Bad input must end as a CaptureError; anything else escaping, a
// crash or a hang is a finding. A file that loads must keep what the reader
// promises: a line for every value, lines within the file, finite values,
// the partial seconds left out counted among the rows read.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_inputs.hpp"
#include "latsim/capture/runtime_stats.hpp"

namespace {

void check(const latsim::capture::RuntimeStats& s, size_t bytes) {
  if (s.rows_read < 0 || s.partial_rows < 0 || s.partial_rows > s.rows_read) std::abort();
  for (const auto& [name, series] : s.series) {
    if (name.empty() || series.values.size() != series.lines.size()) std::abort();
    for (size_t i = 0; i < series.values.size(); ++i) {
      if (!std::isfinite(series.values[i])) std::abort();
      // A line of the file (at most one more than its newlines), or 0: a
      // figure of the whole file (SteamVR's refresh rate and per-second counts).
      if (series.lines[i] < 0 || static_cast<size_t>(series.lines[i]) > bytes + 1) std::abort();
    }
    if (s.find(name) != &series) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto file = latsim::fuzz::write_input("input_runtime_stats.csv", data, size);
  try {
    check(latsim::capture::read_runtime_stats(file), size);
  } catch (const latsim::capture::CaptureError&) {
    // Bad input, reported as the user would see it.
  }
  return 0;
}
