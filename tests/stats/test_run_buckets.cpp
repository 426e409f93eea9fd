// A tick run's histogram buckets worked out in blocks (LogHistogram::add_run,
// bucket_run + add_buckets, RunBucketsCache) against the reference: each
// value of the run added on its own, its bucket taken from its own bits.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <stdexcept>
#include <vector>

#include "latsim/des/random.hpp"
#include "latsim/stats/run_buckets_cache.hpp"
#include "latsim/stats/run_feed.hpp"
#include "latsim/stats/stats.hpp"
#include "latsim/stats/tick_run.hpp"

using latsim::stats::Distribution;
using latsim::stats::i128;
using latsim::stats::LogHistogram;
using latsim::des::RandomStream;
using latsim::stats::RunBuckets;
using latsim::stats::RunBucketsCache;
using latsim::stats::TickRun;
using latsim::stats::tick_run_sums;
using latsim::des::Time;

namespace {

// The reference: every value added alone.
LogHistogram one_by_one(const LogHistogram& shape, const TickRun& run) {
  LogHistogram h(shape.relative_error(), shape.min_positive());
  for (uint64_t i = 0; i < run.count; ++i) h.add(static_cast<double>(run.at(i)));
  return h;
}

void check_same(const LogHistogram& a, const LogHistogram& b) {
  CHECK(a.count() == b.count());
  CHECK(a.min() == b.min());
  CHECK(a.max() == b.max());
  CHECK(a.buckets() == b.buckets());
}

// add_run and bucket_run + add_buckets both against the reference.
void check_run(const LogHistogram& shape, const TickRun& run) {
  INFO("base " << run.base << ", step " << static_cast<double>(run.step) << " / " << static_cast<double>(run.den)
               << ", count " << run.count << ", relative_error " << shape.relative_error() << ", min_positive "
               << shape.min_positive());
  const LogHistogram reference = one_by_one(shape, run);
  LogHistogram walked(shape.relative_error(), shape.min_positive());
  walked.add_run(run);
  check_same(walked, reference);
  RunBuckets b;
  shape.bucket_run(run, b);
  LogHistogram blocked(shape.relative_error(), shape.min_positive());
  blocked.add_buckets(b);
  check_same(blocked, reference);
  // The shortcut for a run within one bucket takes exactly the runs whose
  // values the reference put into a single bucket, as long as they are below
  // 2^53 (beyond, ticks round as doubles and the walk takes them).
  RunBuckets one;
  const bool single = shape.bucket_if_one(run, run.last(), one);
  const double exact = std::ldexp(1.0, 53);
  const bool in_range = std::fabs(static_cast<double>(run.first())) < exact &&
                        std::fabs(static_cast<double>(run.last())) < exact;
  CHECK(single == (in_range && reference.buckets().size() == 1));
  if (single) {
    LogHistogram shortcut(shape.relative_error(), shape.min_positive());
    shortcut.add_buckets(one);
    check_same(shortcut, reference);
  }
}

// The first integer in the bucket of magnitude x (its lower bound rounded up),
// found from the reference alone: the bucket changes between it and its predecessor.
int64_t first_integer_of_bucket(const LogHistogram& shape, int64_t x) {
  const auto bucket_of = [&](int64_t v) {
    LogHistogram h(shape.relative_error(), shape.min_positive());
    h.add(static_cast<double>(v));
    return h.buckets().front().first;
  };
  const double rep = bucket_of(x);
  int64_t good = x, span = 1;  // good: in the bucket; good - span: below it once the gallop stops
  while (bucket_of(good - span) == rep) {
    good -= span;
    span *= 2;
  }
  int64_t bad = good - span;
  while (good - bad > 1) {
    const int64_t mid = bad + (good - bad) / 2;
    (bucket_of(mid) == rep ? good : bad) = mid;
  }
  return good;
}

}  // namespace

TEST_CASE("a tick run bucketed in blocks equals its values added one by one", "[stats][histogram][tick_run]") {
  for (const double relative_error : {0.005, 0.1, 1e-4}) {
    const LogHistogram shape(relative_error);
    // Small integers, where a bucket is narrower than one tick: every value
    // its own block, binade edges at every power of two.
    check_run(shape, TickRun::make(0, 0, 1, 1, 5000));
    // A zero step: one value many times.
    check_run(shape, TickRun::make(42'015'272'244, 5, 0, 7, 1000));
    // Negative values through the zero bucket, a step of 7/3 ticks.
    check_run(shape, TickRun::make(-5000, 1, 7, 3, 5000));
    check_run(shape, TickRun::make(-40'000'000'000, 0, 33'200'000, 1, 2000));
    // Steps of exactly one bucket width (2^35 / S at 2^35 ps, about 34 ms),
    // and a tick either side, so that values fall on and beside bucket edges.
    const int s = shape.buckets_per_binade();
    for (const i128 delta : {i128{-1}, i128{0}, i128{1}}) {
      check_run(shape, TickRun::make(int64_t{1} << 35, 0, (i128{1} << 35) + delta, s, 3000));
      check_run(shape, TickRun::make((int64_t{1} << 35) - 3, 2, (i128{1} << 35) * 3 + delta, 3 * s, 3000));
    }
    // Values one below, at and past the first integer of a bucket.
    const int64_t edge = first_integer_of_bucket(shape, 40'000'000'000);
    for (const int64_t start : {edge - 2, edge - 1, edge})
      check_run(shape, TickRun::make(start, 0, 1, 1, 5));
    // A line's pixel times at 59.94 Hz: 1001e12 / (60000 * 502 * 800) ps each.
    check_run(shape, TickRun::make(33'000'000'000, 0, i128{1001} * 1'000'000'000'000, i128{60000} * 502 * 800, 640));
    // Across 2^53, where ticks round as doubles (value by value).
    check_run(shape, TickRun::make((int64_t{1} << 53) - 1000, 0, 3, 1, 1000));
    check_run(shape, TickRun::make(INT64_MAX - 10'000, 0, 7, 1, 1000));
  }
  // The zero bucket of a histogram whose min_positive is above one tick, and
  // one whose min_positive is the smallest normal double (only 0 is zero).
  check_run(LogHistogram(0.005, 2.5), TickRun::make(-10, 0, 1, 1, 21));
  check_run(LogHistogram(0.005, std::numeric_limits<double>::min()), TickRun::make(-10, 0, 1, 1, 21));
  // A run longer than a million values (two million pixel times).
  check_run(LogHistogram(), TickRun::make(-3'000'000'000, 5, 2'083'333, 500, 2'100'000));
}

TEST_CASE("random tick runs bucketed in blocks equal their values one by one", "[stats][histogram][tick_run]") {
  RandomStream rng(21, "stats.run_buckets");
  const auto between = [&](int64_t lo, int64_t hi) {
    return lo + static_cast<int64_t>(rng.uniform_int(static_cast<uint64_t>(hi - lo) + 1));
  };
  for (int trial = 0; trial < 300; ++trial) {
    const auto den = static_cast<i128>(between(1, 100'000'000));
    // Steps from a small fraction of a tick to a few bucket widths at the base.
    const i128 step = den * between(0, trial % 2 == 0 ? 20 : 2'000'000'000) + between(0, static_cast<int64_t>(den) - 1);
    const int64_t base = between(-60'000'000'000, 60'000'000'000);
    check_run(LogHistogram(trial % 3 == 0 ? 0.02 : 0.005),
              TickRun::make(base, between(0, static_cast<int64_t>(den) - 1), step, den,
                            static_cast<uint64_t>(between(1, 3000))));
  }
}

TEST_CASE("remembered run buckets give the histogram of the runs themselves", "[stats][histogram][tick_run]") {
  // Fields of a display: the same display-delay run every field, and
  // latencies whose base moves; three histogram shapes share one cache.
  RunBucketsCache cache;
  const TickRun delays = TickRun::make(0, 0, i128{800} * 1'000'000'000'000, i128{60} * 502 * 800, 480);
  Distribution fine, coarse(0.05), loop, loop_coarse(0.05);
  for (int field = 0; field < 200; ++field) {
    const TickRun latencies = delays.shifted(34'000'000'000 + 1'000'003 * (field % 7));
    for (const TickRun& run : {delays, latencies, latencies}) {
      fine.add_run(tick_run_sums(run), cache.buckets(fine.histogram(), run));
      coarse.add_run(tick_run_sums(run), cache.buckets(coarse.histogram(), run));
      for (uint64_t i = 0; i < run.count; ++i) {
        loop.add(Time::ps(run.at(i)));
        loop_coarse.add(Time::ps(run.at(i)));
      }
    }
  }
  check_same(fine.histogram(), loop.histogram());
  check_same(coarse.histogram(), loop_coarse.histogram());
  CHECK(fine.stats().mean() == loop.stats().mean());
  CHECK(fine.stats().variance() == loop.stats().variance());
  // Buckets worked out for another shape are refused.
  RunBuckets b;
  LogHistogram(0.05).bucket_run(delays, b);
  LogHistogram other;
  CHECK_THROWS_AS(other.add_buckets(b), std::invalid_argument);
  CHECK(other.count() == 0);
}

TEST_CASE("a distribution keeps a bucketed run's samples", "[stats][tick_run]") {
  const TickRun run = TickRun::make(1'000, 1, 10, 3, 50);
  RunBuckets b;
  Distribution kept(0.005, true), loop(0.005, true);
  kept.histogram().bucket_run(run, b);
  kept.add_run(tick_run_sums(run), b);
  for (uint64_t i = 0; i < run.count; ++i) loop.add(Time::ps(run.at(i)));
  CHECK(kept.samples() == loop.samples());
  CHECK(kept.summary().p90 == loop.summary().p90);
  Distribution plain;
  plain.add(1.0);
  CHECK_THROWS_AS(plain.add_run(tick_run_sums(run), b), std::logic_error);
  CHECK(plain.count() == 1);
}

TEST_CASE("runs fed a line at a time are gathered into the figures of the lines added one by one",
          "[stats][tick_run]") {
  using latsim::stats::RunFeed;
  using latsim::stats::TickStepper;
  // 60 Hz, 502 lines of 800 pixel times: a line every 1e12 / (60 * 502) ps.
  const i128 den = i128{60} * 502 * 800, line_step = i128{800} * 1'000'000'000'000;
  RunFeed feed;
  Distribution mtp, shown, loop_mtp, loop_shown;
  for (int64_t field = 0; field < 30; ++field) {
    // The field's lines, one event each, as the display paces them.
    TickStepper line(TickRun::make(0, field * 502 * line_step, line_step, den, 480));
    // The image, hence the origin, changes mid-field every third field (a
    // swap during scanout), which must close the gathered run.
    for (int j = 0; j < 480; ++j, line.step()) {
      const int64_t origin = field * 16'000'000'000 - (field % 3 == 0 && j >= 200 ? 5'000'000 : 0);
      const int64_t scan_start = field * 16'666'666'667;
      feed.add(0, line.run_from_here(line_step, 1), {{&mtp, origin}, {&shown, scan_start}});
      loop_mtp.add(Time::ps(line.ticks() - origin));
      loop_shown.add(Time::ps(line.ticks() - scan_start));
    }
    // A value added another way after closing the run, as the recorder does.
    feed.close(&mtp);
    mtp.add(Time::ps(7));
    loop_mtp.add(Time::ps(7));
  }
  feed.close_all();
  for (const auto& [a, b] : {std::pair{&mtp, &loop_mtp}, std::pair{&shown, &loop_shown}}) {
    check_same(a->histogram(), b->histogram());
    CHECK(std::bit_cast<uint64_t>(a->stats().mean()) == std::bit_cast<uint64_t>(b->stats().mean()));
    CHECK(std::bit_cast<uint64_t>(a->stats().variance()) == std::bit_cast<uint64_t>(b->stats().variance()));
  }
  CHECK(mtp.count() == 30 * 481);
  // More than four targets are refused.
  Distribution d;
  CHECK_THROWS_AS(feed.add(1, TickRun::single(1), {{&d, 0}, {&d, 0}, {&d, 0}, {&d, 0}, {&d, 0}}),
                  std::invalid_argument);
}

TEST_CASE("runs whose step and den need more than 64 bits are gathered into the values of the direct formula",
          "[stats][tick_run]") {
  using latsim::stats::RunFeed;
  using latsim::stats::TickStepper;
  // A den of 2^70 + 12345 and a step of 3 den + 2^66 + 7: three whole ticks
  // a line, and a remainder with high bits that carries into a fourth tick
  // about every sixteenth line (2^66 / 2^70).
  const i128 den = (i128{1} << 70) + 12345, step = 3 * den + (i128{1} << 66) + 7;
  const TickRun field = TickRun::make(1'000, (i128{1} << 69) + 99, step, den, 3000);
  RunFeed feed;
  Distribution gathered, direct;
  TickStepper line(field);
  for (uint64_t i = 0; i < field.count; ++i, line.step()) {
    // The origin moves at line 1700, which closes the gathered run.
    const int64_t origin = i < 1700 ? 0 : 500;
    feed.add(0, line.run_from_here(step, 1), {{&gathered, origin}});
    // v_i = base + floor((offset + i step) / den), by one division of its own.
    const i128 v = i128{1'000} + ((i128{1} << 69) + 99 + static_cast<i128>(i) * step) / den;
    direct.add(Time::ps(static_cast<int64_t>(v) - origin));
  }
  feed.close_all();
  check_same(gathered.histogram(), direct.histogram());
  CHECK(gathered.count() == 3000);
  CHECK(std::bit_cast<uint64_t>(gathered.stats().mean()) == std::bit_cast<uint64_t>(direct.stats().mean()));
  CHECK(std::bit_cast<uint64_t>(gathered.stats().variance()) == std::bit_cast<uint64_t>(direct.stats().variance()));
  CHECK(gathered.stats().min() == direct.stats().min());
  CHECK(gathered.stats().max() == direct.stats().max());
}
