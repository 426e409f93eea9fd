// Adding runs of durations to distributions at the price of their information.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "latsim/des/run_buckets_cache.hpp"
#include "latsim/des/stats.hpp"
#include "latsim/des/tick_run.hpp"

namespace latsim::des {

/// A distribution that takes a run of instants as durations from `origin`.
struct RunTarget {
  Distribution* d = nullptr;
  int64_t origin = 0;  // picoseconds
  bool operator==(const RunTarget&) const = default;
};

/// Adds tick runs of durations to distributions, gathering runs that continue
/// one another into one closed-form add.
///
/// Each slot holds one open run of instants with up to four targets: a run
/// for the same targets that holds the next instant of the open one at its
/// pace (the next line of a field, one event at a time) extends it with a
/// comparison; any other run closes it (adds it to every target) and opens
/// anew. A closed run's sums and buckets come from caches (they recur field
/// after field). Moments are exact and histogram counts are the values', so
/// the figures equal those of the runs added one by one; only kept samples
/// arrive later, a gathered run at a time. Close a distribution's run before
/// it takes a value another way, and close all before distributions are read.
class RunFeed {
 public:
  static constexpr size_t kMaxTargets = 4;
  static constexpr uint64_t kMaxGathered = uint64_t{1} << 20;  // the longest run the sums cache takes
  /// Adds v - t.origin for every instant v of `run` to each target t, through
  /// `slot`; at most kMaxTargets targets (std::invalid_argument otherwise).
  void add(size_t slot, const TickRun& run, std::initializer_list<RunTarget> targets) {
    if (slot < open_.size() && extend(open_[slot], run, targets)) [[likely]] return;
    add_anew(slot, run, targets);
  }
  /// Adds the open run that goes to d, if any.
  void close(const Distribution* d);
  /// Adds every open run.
  void close_all();

 private:
  struct Open {
    std::array<RunTarget, kMaxTargets> targets{};
    size_t n_targets = 0;
    TickRun run;  // count 0: nothing open
    // Where the run's next instant lies (base and normalised offset), and
    // the whole ticks and remainder of a step: continuing is a comparison.
    int64_t end_base = 0;
    i128 end_offset = 0;
    int64_t whole = 0;
    i128 fraction = 0;
  };
  // Extends the open run by `run` if it is the single instant one step past
  // it (offsets of both normalised to [0, den)) for the same targets.
  static bool extend(Open& o, const TickRun& run, std::initializer_list<RunTarget> targets) {
    if (run.base != o.end_base || run.count != 1 || o.run.count == 0 || o.run.count >= kMaxGathered ||
        run.offset != o.end_offset || run.step != o.run.step || run.den != o.run.den || targets.size() != o.n_targets)
      return false;
    const RunTarget* t = o.targets.data();
    for (const RunTarget& target : targets)
      if (!(target == *t++)) return false;
    ++o.run.count;
    o.end_base += o.whole;
    o.end_offset += o.fraction;
    if (o.end_offset >= o.run.den) {
      o.end_offset -= o.run.den;
      ++o.end_base;
    }
    return true;
  }
  void add_anew(size_t slot, const TickRun& run, std::initializer_list<RunTarget> targets);
  void open(Open& o, const TickRun& run, std::initializer_list<RunTarget> targets);
  void close(Open& o);

  std::vector<Open> open_;
  TickRunSumsCache sums_;
  RunBucketsCache buckets_;
};

}  // namespace latsim::des
