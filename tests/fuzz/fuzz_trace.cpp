// Fuzz target: a head-motion trace file (latsim CSV or the MMSys 2018 head
// trace format). Bad input must end as a TraceError; anything else escaping,
// a crash or a hang is a finding. A trace that loads must hold what the
// loader promises: increasing times and unit quaternions.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_inputs.hpp"
#include "latsim/tracker/trace.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto file = latsim::fuzz::write_input("input_trace.txt", data, size);
  try {
    const latsim::tracker::Trace trace = latsim::tracker::load_trace(file);
    for (size_t i = 0; i < trace.samples.size(); ++i) {
      const auto& q = trace.samples[i].pose.orientation;
      const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
      if (!(std::fabs(norm - 1.0) < 1e-6)) std::abort();
      if (i > 0 && !(trace.samples[i - 1].t < trace.samples[i].t)) std::abort();
    }
  } catch (const latsim::tracker::TraceError&) {
  }
  return 0;
}
