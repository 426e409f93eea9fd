#include "latsim/stats/run_feed.hpp"

#include <algorithm>
#include <stdexcept>

namespace latsim::stats {

void RunFeed::add_anew(size_t slot, const TickRun& run, std::initializer_list<RunTarget> targets) {
  if (run.count == 0) return;
  if (targets.size() > kMaxTargets) throw std::invalid_argument("RunFeed::add: at most four targets");
  if (slot >= open_.size()) open_.resize(slot + 1);
  Open& o = open_[slot];
  close(o);
  if (run.count > kMaxGathered) {
    for (const RunTarget& t : targets) t.d->add_run(run.shifted(-t.origin));  // in chunks, on its own
    return;
  }
  open(o, run, targets);
}

void RunFeed::open(Open& o, const TickRun& run, std::initializer_list<RunTarget> targets) {
  std::copy(targets.begin(), targets.end(), o.targets.begin());
  o.n_targets = targets.size();
  o.run = run;
  const TickStepper end(run, run.count);  // where the next instant would lie
  o.end_base = end.ticks();
  o.end_offset = Halves::of(end.remainder());
  if (!o.step.equals(run.step) || !o.den.equals(run.den)) {  // the same pace as last time: no division
    o.whole = static_cast<int64_t>(run.step / run.den);
    o.fraction = run.step % run.den;
    o.step = Halves::of(run.step);
    o.den = Halves::of(run.den);
  }
}

void RunFeed::close(Open& o) {
  if (o.run.count == 0) return;
  // Targets often share an origin (motion-to-photon, rotation and
  // translation latency of an image whose pose comes from one sample): the
  // next target of the same origin and histogram shape takes the buckets just
  // worked out (valid until the cache's next call) and the same sums.
  const RunBuckets* last = nullptr;
  int64_t last_origin = 0;
  const LogHistogram* last_shape = nullptr;
  const TickRunSums* sums = nullptr;
  TickRunMoments moments;
  for (size_t i = 0; i < o.n_targets; ++i) {
    const RunTarget& t = o.targets[i];
    if (o.run.count == 1) {
      t.d->add(des::Time::ps(o.run.shifted(-t.origin).base));
      continue;
    }
    const LogHistogram& shape = t.d->histogram();
    if (last == nullptr || t.origin != last_origin || last_shape->buckets_per_binade() != shape.buckets_per_binade() ||
        last_shape->min_positive() != shape.min_positive()) {
      last = &buckets_.buckets(shape, o.run.shifted(-t.origin));
      if (sums == nullptr) sums = &sums_.sums(last->run);  // the same for every origin
      if (last_shape == nullptr || t.origin != last_origin) moments = tick_run_moments(last->run, *sums);
      last_origin = t.origin;
      last_shape = &shape;
    }
    t.d->add_run(*sums, *last, moments);
  }
  o.run.count = 0;
}

void RunFeed::close(const Distribution* d) {
  for (Open& o : open_) {
    if (o.run.count == 0) continue;
    const auto goes_to_d = [d](const RunTarget& t) { return t.d == d; };
    if (std::any_of(o.targets.begin(), o.targets.begin() + static_cast<std::ptrdiff_t>(o.n_targets), goes_to_d))
      close(o);
  }
}

void RunFeed::close_all() {
  for (Open& o : open_) close(o);
}

}  // namespace latsim::stats
