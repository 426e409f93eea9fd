// Just-in-time application pacing and its miss-rate-holding variant.
#pragma once

#include <deque>
#include <memory>

#include "frame_stages/pacing.hpp"

namespace latsim::pipelines::frame_stages {

/// The last `capacity` measured frame times and their nearest-rank percentiles.
class RecentSpans {
 public:
  explicit RecentSpans(int capacity) : capacity_(capacity) {}
  void add(des::Time span);
  bool empty() const { return spans_.empty(); }
  /// The smallest span at or above `percent` of them (nearest rank); needs !empty().
  des::Time percentile(double percent) const;

 private:
  int capacity_;
  std::deque<des::Time> spans_;
};

/// Wakes the frame its chosen percentile of recent frame times plus a fixed margin before the latch.
std::unique_ptr<AppPacer> make_just_in_time_pacer(const JustInTimeParams& p);
/// Wakes the frame the median recent frame time plus a margin before the
/// latch; the margin rises at each miss and falls while misses per minute are below target.
std::unique_ptr<AppPacer> make_miss_rate_pacer(const MissRateParams& p);

}  // namespace latsim::pipelines::frame_stages
