// Adding runs of durations to distributions at the price of their information.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "latsim/stats/run_buckets_cache.hpp"
#include "latsim/stats/stats.hpp"
#include "latsim/stats/tick_run.hpp"

namespace latsim::stats {

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
  /// Extends the open run of `slot` by `run` if it is the single instant one
  /// step past it, for the targets that run has (the caller knows they are
  /// the same as add() would be given); false otherwise, with nothing done.
  bool extend_run(size_t slot, const TickRun& run) { return slot < open_.size() && extend_pace(open_[slot], run); }
  /// Adds the open run that goes to d, if any.
  void close(const Distribution* d);
  /// Adds every open run.
  void close_all();

 private:
  // A 128-bit integer kept as two 64-bit halves. extend() runs on every line
  // and reads what the previous line wrote; GCC loads a 128-bit member with
  // one vector load and spills it to the stack to split it, and neither that
  // load (of two 64-bit stores) nor the split (of a vector store) is forwarded
  // from the store buffer: a stall on every line. Halves are read and written
  // with 64-bit moves.
  struct Halves {
    uint64_t lo = 0;
    uint64_t hi = 0;
    static Halves of(i128 v) { return {static_cast<uint64_t>(v), static_cast<uint64_t>(static_cast<u128>(v) >> 64)}; }
    i128 value() const { return static_cast<i128>((static_cast<u128>(hi) << 64) | lo); }
    bool equals(i128 v) const {
      return lo == static_cast<uint64_t>(v) && hi == static_cast<uint64_t>(static_cast<u128>(v) >> 64);
    }
  };
  struct Open {
    std::array<RunTarget, kMaxTargets> targets{};
    size_t n_targets = 0;
    TickRun run;  // count 0: nothing open
    // Where the run's next instant lies (base and normalised offset), the
    // run's step and den, and the whole ticks and remainder of a step:
    // continuing is a comparison.
    int64_t end_base = 0;
    Halves end_offset, step, den;
    int64_t whole = 0;
    i128 fraction = 0;
  };
  // Extends the open run by `run` if it is the single instant one step past
  // it (offsets of both normalised to [0, den)) for the same targets.
  static bool extend(Open& o, const TickRun& run, std::initializer_list<RunTarget> targets) {
    if (targets.size() != o.n_targets) return false;
    const RunTarget* t = o.targets.data();
    for (const RunTarget& target : targets)
      if (!(target == *t++)) return false;
    return extend_pace(o, run);
  }
  // The same, whatever the targets.
  static bool extend_pace(Open& o, const TickRun& run) {
    if (run.base != o.end_base || run.count != 1 || o.run.count == 0 || o.run.count >= kMaxGathered) return false;
    if (!o.end_offset.equals(run.offset) || !o.step.equals(run.step) || !o.den.equals(run.den)) return false;
    ++o.run.count;
    o.end_base += o.whole;
    i128 end_offset = o.end_offset.value() + o.fraction;
    if (end_offset >= o.den.value()) {
      end_offset -= o.den.value();
      ++o.end_base;
    }
    o.end_offset = Halves::of(end_offset);
    return true;
  }
  void add_anew(size_t slot, const TickRun& run, std::initializer_list<RunTarget> targets);
  void open(Open& o, const TickRun& run, std::initializer_list<RunTarget> targets);
  void close(Open& o);

  std::vector<Open> open_;
  TickRunSumsCache sums_;
  RunBucketsCache buckets_;
};

}  // namespace latsim::stats
