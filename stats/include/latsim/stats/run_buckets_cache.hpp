// Remembering how recent tick runs fall into histogram buckets.
#pragma once

#include <cstddef>
#include <vector>

#include "latsim/stats/reused_table.hpp"
#include "latsim/stats/stats.hpp"
#include "latsim/stats/tick_run.hpp"

namespace latsim::stats {

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
  // Room for the lines of a few fields: at pixel level every line is a run,
  // and a field's display delays recur only fields later (60 Hz on the
  // picosecond grid repeats its phase every third field: 1,440 line runs).
  // An entry is the buckets of its run in its shape, whoever left it: the
  // table is reused from run to run (per_binade 0: an empty slot).
  static constexpr size_t kSize = 4096;
  ReusedTable<RunBuckets, kSize> table_;
  RunBuckets one_;  // a run within one bucket, worked out without the table
};

}  // namespace latsim::stats
