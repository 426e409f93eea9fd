// Remembering how recent tick runs fall into histogram buckets.
#pragma once

#include <array>
#include <cstddef>

#include "latsim/des/stats.hpp"
#include "latsim/des/tick_run.hpp"

namespace latsim::des {

/// Remembers how recent tick runs fall into the buckets of a histogram shape.
///
/// Runs recur: a field's display delays (photon times from the start of its
/// scanout) are the same run field after field, and a span's motion-to-photon,
/// rotation and translation latencies are one run whenever the image's
/// orientation and position come from one sample. A remembered run is added
/// with one increment per bucket instead of a walk through its values; what is
/// remembered depends only on the run and the shape, so hits and misses give
/// the same histogram.
class RunBucketsCache {
 public:
  /// The buckets of `run` in histograms shaped like `h` (worked out on a miss;
  /// valid until the next call).
  const RunBuckets& buckets(const LogHistogram& h, const TickRun& run);

 private:
  static constexpr size_t kSize = 64;
  std::array<RunBuckets, kSize> table_;  // per_binade 0: an empty slot
};

}  // namespace latsim::des
