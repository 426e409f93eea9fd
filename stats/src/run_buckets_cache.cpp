#include "latsim/stats/run_buckets_cache.hpp"

namespace latsim::stats {

const RunBuckets& RunBucketsCache::buckets(const LogHistogram& h, const TickRun& run) {
  // A run within one bucket costs less to work out than to look up.
  if (run.count > 0 && h.bucket_if_one(run, run.last(), one_)) return one_;
  const auto key = (static_cast<uint64_t>(run.base) ^ static_cast<uint64_t>(run.offset)) * 0x9E3779B97F4A7C15ull ^
                   run.count;
  RunBuckets& e = table_[(key >> 40) % kSize];
  const TickRun& r = e.run;
  const bool hit = r.base == run.base && r.offset == run.offset && r.step == run.step && r.den == run.den &&
                   r.count == run.count && e.per_binade == h.buckets_per_binade() &&
                   e.min_positive == h.min_positive();
  if (!hit) h.bucket_run(run, e);
  return e;
}

}  // namespace latsim::stats
