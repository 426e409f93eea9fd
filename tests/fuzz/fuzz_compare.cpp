// Fuzz target: a capture as `latsim compare` reads it. The kind of file is
// told from its header (file_generation); a PresentMon capture is then read
// for each process choice compare offers, with its process list, display
// refresh period and replay warnings, and every quantity compare sets side by
// side goes through the sample statistics and the KS distance against the
// same quantity of a shipped capture; a runtime's statistics file is read as
// compare reads it. Bad input must end as a CaptureError; anything else
// escaping, a crash or a hang is a finding. What the reader promises is
// checked: frames in file order, finite values, statistics that are ordered
// and a KS distance in [0, 1]. (The run side, a run directory, is not fuzzed.)
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <optional>
#include <vector>

#include "fuzz_inputs.hpp"
#include "latsim/capture/capture.hpp"
#include "latsim/capture/comparison.hpp"
#include "latsim/capture/presentmon.hpp"
#include "latsim/capture/runtime_stats.hpp"

namespace {

namespace cap = latsim::capture;
using Field = std::function<std::optional<double>(const cap::PresentMonFrame&)>;

// The quantities compare's PresentMon rows read of a frame.
const std::vector<Field>& fields() {
  static const std::vector<Field> f{
      [](const cap::PresentMonFrame& x) { return x.between_presents_ms; },
      [](const cap::PresentMonFrame& x) { return x.in_present_ms; },
      [](const cap::PresentMonFrame& x) { return x.cpu_busy_ms; },
      [](const cap::PresentMonFrame& x) { return x.gpu_busy_ms; },
      [](const cap::PresentMonFrame& x) { return x.gpu_time_ms; },
      [](const cap::PresentMonFrame& x) { return x.until_displayed_ms; },
      [](const cap::PresentMonFrame& x) { return x.between_display_change_ms; },
  };
  return f;
}

std::vector<double> values_of(const cap::PresentMonProcess& p, const Field& field) {
  std::vector<double> out;
  for (const auto& frame : p.frames)
    if (const auto v = field(frame)) {
      if (!std::isfinite(*v)) std::abort();
      out.push_back(*v);
    }
  return out;
}

void check_stats(const std::vector<double>& values) {
  const cap::SampleStats s = cap::sample_stats(values);
  if (s.count != static_cast<int64_t>(values.size())) std::abort();
  if (values.empty()) return;
  if (!s.min || !s.p50 || !s.p99 || !s.max || !s.mean) std::abort();
  if (!(*s.min <= *s.p50 && *s.p50 <= *s.p99 && *s.p99 <= *s.max)) std::abort();
}

// A shipped capture of one process: the other side of every distance.
const cap::PresentMonProcess& reference() {
  static const cap::PresentMonProcess p =
      cap::read_presentmon(latsim::fuzz::mirror_dir() / "test_case_0.csv", {"", std::nullopt});
  return p;
}

void compare_presentmon(const std::filesystem::path& file, const cap::ProcessSelect& select) {
  const cap::PresentMonProcess p = cap::read_presentmon(file, select);
  if (p.frames.empty() || static_cast<int64_t>(p.frames.size()) > p.rows_read) std::abort();
  for (size_t i = 1; i < p.frames.size(); ++i)
    if (p.frames[i].line <= p.frames[i - 1].line) std::abort();
  const auto period = cap::refresh_period_ms(file);
  if (period && !(std::isfinite(*period) && *period > 0)) std::abort();
  (void)cap::presentmon_warnings(p, period, 90.0, true);
  (void)p.mode(), (void)p.sync_interval(), (void)p.allows_tearing();
  for (const Field& field : fields()) {
    const std::vector<double> values = values_of(p, field);
    check_stats(values);
    const auto ks = cap::ks_distance(values, values_of(reference(), field));
    if (ks && !(*ks >= 0.0 && *ks <= 1.0)) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto file = latsim::fuzz::write_input("input_compare.csv", data, size);
  try {
    const cap::Generation g = cap::file_generation(file);
    if (!cap::is_presentmon(g)) {
      (void)cap::read_runtime_stats(file);
      return 0;
    }
    const auto processes = cap::presentmon_processes(file);
    // compare's choices: none (one process only), then each process by name and by id.
    try {
      compare_presentmon(file, {"", std::nullopt});
    } catch (const cap::CaptureError&) {
    }
    for (const auto& pc : processes) {
      if (pc.frames <= 0) std::abort();
      try {
        compare_presentmon(file, {pc.application, pc.process_id});
      } catch (const cap::CaptureError&) {
      }
    }
  } catch (const cap::CaptureError&) {
    // Bad input, reported as the user would see it.
  }
  return 0;
}
