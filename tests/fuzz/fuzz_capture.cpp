// Fuzz target: a frame-timing capture (PresentMon's three column sets or any
// CSV). Bad input must end as a CaptureError; anything else escaping, a crash
// or a hang is a finding. A capture that loads must keep what the reader
// promises: every selected row is a value or a counted skip of each column,
// and the rows of the file are the selected ones and the others.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>

#include "fuzz_inputs.hpp"
#include "latsim/capture/capture.hpp"

namespace {

void check(const latsim::capture::Capture& c) {
  if (c.rows_selected + c.rows_of_other_processes != c.rows_read) std::abort();
  for (const auto& col : c.columns) {
    const auto accounted = static_cast<int64_t>(col.values.size()) + col.skipped_na + col.skipped_not_displayed;
    if (col.values.empty() || accounted != c.rows_selected) std::abort();
    if (col.min_line < 2 || col.max_line < 2 || col.min() > col.max()) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto file = latsim::fuzz::write_input("input_capture.csv", data, size);
  // Columns of each generation (a display column among them) and a generic name.
  for (const char* column : {"MsGPUBusy", "MsUntilDisplayed", "msUntilDisplayed", "msGPUActive", "GPUBusy", "ms"}) {
    for (const std::optional<int64_t> pid : {std::optional<int64_t>(), std::optional<int64_t>(1268)}) {
      try {
        check(latsim::capture::read_capture(file, {{column}, {"", pid}}));
      } catch (const latsim::capture::CaptureError&) {
      }
    }
  }
  return 0;
}
