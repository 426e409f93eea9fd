#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "finite_sample.hpp"
#include "latsim/stats/stats.hpp"

namespace latsim::stats {

namespace {

constexpr uint64_t kHidden = uint64_t{1} << 52;

// The first 52-bit fraction of sub-bucket k of S in a binade: ceil(k 2^52 / S),
// so that floor(fraction S / 2^52) = k exactly from there to the next one.
uint64_t lower_fraction(int32_t k, int32_t per_binade) {
  return static_cast<uint64_t>(((static_cast<u128>(k) << 52) + static_cast<u128>(per_binade) - 1) /
                               static_cast<u128>(per_binade));
}

}  // namespace

void LogHistogram::reject_non_finite(double x) { throw_non_finite(x, "LogHistogram::add"); }

void LogHistogram::DenseCounts::grow_and_add(int32_t index, uint64_t weight) {
  if (counts_.empty()) {
    offset_ = index;
    counts_.assign(1, 0);
  }
  // Each growth adds an eighth of the current span as slack, so growth is
  // amortised O(1); unused slack can sit at both ends, which still keeps the
  // allocation within 4/3 of the range of buckets seen (c = 1 + 2c/8).
  const auto slack = static_cast<int32_t>(counts_.size() / 8);
  if (index < offset_) {
    const int32_t new_offset = index - slack;
    counts_.insert(counts_.begin(), static_cast<size_t>(offset_ - new_offset), 0);
    offset_ = new_offset;
  } else if (index >= end_index()) {
    counts_.resize(static_cast<size_t>(index - offset_ + 1 + slack), 0);
  }
  counts_[static_cast<size_t>(index - offset_)] += weight;
}

void LogHistogram::DenseCounts::add_blocks(const std::vector<RunBuckets::Block>& blocks) {
  if (blocks.empty()) return;
  const auto [lo, hi] = std::minmax(blocks.front().bucket, blocks.back().bucket);
  if (lo < offset_ || counts_.empty()) grow_and_add(lo, 0);
  if (hi >= end_index()) grow_and_add(hi, 0);
  for (const RunBuckets::Block& block : blocks) counts_[static_cast<size_t>(block.bucket - offset_)] += block.count;
}

uint64_t LogHistogram::DenseCounts::at(int32_t index) const {
  if (index < offset_ || index >= end_index()) return 0;
  return counts_[static_cast<size_t>(index - offset_)];
}

LogHistogram::LogHistogram(double relative_error, double min_positive)
    : relative_error_(relative_error), min_positive_(min_positive) {
  if (!(relative_error >= 1e-4 && relative_error <= 0.5)) {
    throw std::invalid_argument("LogHistogram: relative_error must be in [1e-4, 0.5], got " +
                                std::to_string(relative_error));
  }
  if (!(std::isfinite(min_positive) && min_positive >= std::numeric_limits<double>::min())) {
    throw std::invalid_argument("LogHistogram: min_positive must be finite and at least 2.2e-308 (DBL_MIN)");
  }
  // The smallest S with 1 / (2 S + 1) < relative_error.
  per_binade_ = static_cast<int32_t>(std::floor((1.0 / relative_error - 1.0) / 2.0)) + 1;
  for (int32_t k = 0; k <= per_binade_; ++k) lower_fraction_.push_back(lower_fraction(k, per_binade_));
}

double LogHistogram::bucket_lower(int32_t index) const {
  const int32_t exponent = index / per_binade_, sub = index % per_binade_;
  return std::bit_cast<double>((static_cast<uint64_t>(exponent) << 52) | lower_fraction_[static_cast<size_t>(sub)]);
}

double LogHistogram::representative(int32_t index) const {
  // 2 lo hi / (lo + hi) on the bucket's integer mantissas, scaled at the end
  // so that the topmost bucket (hi = 2^1024) needs no infinity.
  const int32_t exponent = index / per_binade_, sub = index % per_binade_;
  const auto lo = static_cast<double>(kHidden + lower_fraction_[static_cast<size_t>(sub)]);
  const auto hi = static_cast<double>(kHidden + lower_fraction_[static_cast<size_t>(sub) + 1]);
  return std::ldexp(2.0 * lo * hi / (lo + hi), exponent - 1075);
}

double LogHistogram::next_bucket_start(double x) const {
  const double magnitude = std::fabs(x);
  if (magnitude < min_positive_) return min_positive_;
  if (x > 0.0) {
    // The next sub-bucket's first fraction in the same binade, or the next binade.
    const auto bits = std::bit_cast<uint64_t>(magnitude);
    const uint64_t exponent = bits >> 52;
    const auto sub = static_cast<size_t>((static_cast<u128>(bits & (kHidden - 1)) * static_cast<u128>(per_binade_)) >> 52);
    if (sub + 1 < static_cast<size_t>(per_binade_))
      return std::bit_cast<double>((exponent << 52) | lower_fraction_[sub + 1]);
    if (exponent + 1 >= 2047) return std::numeric_limits<double>::infinity();
    return std::bit_cast<double>((exponent + 1) << 52);
  }
  // Negative: the bucket holds on while |v| >= its lower edge (and min_positive).
  const double edge = std::max(bucket_lower(bucket_index(magnitude)), min_positive_);
  return std::nextafter(-edge, 0.0);
}

void LogHistogram::add(double x, uint64_t weight) {
  require_finite(x, "LogHistogram::add");
  if (weight == 0) return;
  add_to_bucket(x, weight);
  seen_.note(x, x, weight);
}

template <class OnBlock>
void LogHistogram::walk_run(const TickRun& run, OnBlock&& on_block) const {
  constexpr double kExact = 9007199254740992.0;  // 2^53: beyond it, ticks round as doubles
  const int64_t last = run.last();
  if (std::fabs(static_cast<double>(run.first())) >= kExact || std::fabs(static_cast<double>(last)) >= kExact) {
    for (uint64_t i = 0; i < run.count; ++i) on_block(static_cast<double>(run.at(i)), 1);
    return;
  }
  // A run within one bucket (the pixels of a line, most often): one block,
  // with no walk at all.
  if (const auto first = static_cast<double>(run.first()); static_cast<double>(last) < next_bucket_start(first)) {
    on_block(first, run.count);
    return;
  }
  // Values never decrease: each bucket holds a contiguous block of indices,
  // ending where the run first reaches the next bucket's start (an integer
  // reaches a double bound b exactly when it reaches ceil(b)). A block of a
  // few values is walked with the stepper; a longer one is jumped over in
  // closed form (two divisions).
  const double ticks_per_value = static_cast<double>(run.step) / static_cast<double>(run.den);
  TickStepper t(run);
  for (uint64_t i = 0; i < run.count;) {
    const int64_t v = t.ticks();
    const auto x = static_cast<double>(v);
    const double next = next_bucket_start(x);
    uint64_t j = i;
    if (!(next < kExact)) {
      j = run.count;  // every later value (all below 2^53) stays in this bucket
    } else if (const auto limit = static_cast<int64_t>(std::ceil(next)); next - x <= 16.0 * ticks_per_value) {
      do {
        ++j;
        t.step();
      } while (j < run.count && t.ticks() < limit);
    } else {
      j = std::max(i + 1, run.first_index_at_or_above(limit));
      if (j < run.count) t = TickStepper(run, j);
    }
    on_block(x, j - i);
    i = j;
  }
}

void LogHistogram::add_run(const TickRun& run) {
  if (run.count == 0) return;
  walk_run(run, [this](double x, uint64_t n) { add_to_bucket(x, n); });
  seen_.note(static_cast<double>(run.first()), static_cast<double>(run.last()), run.count);
}

void LogHistogram::start_buckets(const TickRun& run, int64_t last, RunBuckets& out) const {
  out.run = run;
  out.per_binade = per_binade_;
  out.min_positive = min_positive_;
  out.negative.clear();
  out.zero = 0;
  out.positive.clear();
  out.last = last;
}

void LogHistogram::add_block(double x, uint64_t n, RunBuckets& out) const {
  const double magnitude = std::fabs(x);
  if (magnitude < min_positive_) {
    out.zero += n;
  } else {
    (x > 0.0 ? out.positive : out.negative).push_back({bucket_index(magnitude), n});
  }
}

void LogHistogram::bucket_run(const TickRun& run, RunBuckets& out) const {
  start_buckets(run, run.count == 0 ? run.base : run.last(), out);
  if (run.count == 0) return;
  walk_run(run, [this, &out](double x, uint64_t n) { add_block(x, n, out); });
}

bool LogHistogram::bucket_if_one(const TickRun& run, int64_t last, RunBuckets& out) const {
  constexpr double kExact = 9007199254740992.0;  // 2^53, as in walk_run
  const auto first = static_cast<double>(run.first()), end = static_cast<double>(last);
  if (run.count == 0 || !(std::fabs(first) < kExact && std::fabs(end) < kExact && end < next_bucket_start(first)))
    return false;
  start_buckets(run, last, out);
  add_block(first, run.count, out);
  return true;
}

void LogHistogram::add_buckets(const RunBuckets& b) {
  if (b.per_binade != per_binade_ || b.min_positive != min_positive_) {
    throw std::invalid_argument(
        "LogHistogram::add_buckets: the run was bucketed for another relative_error or min_positive");
  }
  if (b.run.count == 0) return;
  negative_.add_blocks(b.negative);
  zero_count_ += b.zero;
  positive_.add_blocks(b.positive);
  seen_.note(static_cast<double>(b.run.first()), static_cast<double>(b.last), b.run.count);
}

void LogHistogram::add_arithmetic_run(double first, double step, uint64_t n) {
  require_finite(first, "LogHistogram::add_arithmetic_run (first)");
  require_finite(step, "LogHistogram::add_arithmetic_run (step)");
  if (n == 0) return;
  const auto value = [&](uint64_t i) { return first + static_cast<double>(i) * step; };
  require_finite(value(n - 1), "LogHistogram::add_arithmetic_run (last value)");
  // Rounded values are monotone in i, so buckets come in contiguous blocks:
  // find each block's end by galloping, then bisecting.
  const auto key = [&](double x) -> int64_t {
    const double m = std::fabs(x);
    if (m < min_positive_) return 0;
    return (x > 0.0 ? 1 : -1) * (static_cast<int64_t>(bucket_index(m)) + 1);
  };
  for (uint64_t i = 0; i < n;) {
    const double x = value(i);
    const int64_t k = key(x);
    uint64_t good = i, span = 1;
    while (good + span < n && key(value(good + span)) == k) {
      good += span;
      span *= 2;
    }
    uint64_t bad = std::min(n, good + span);  // first index known or assumed outside
    while (bad - good > 1) {
      const uint64_t mid = good + (bad - good) / 2;
      (key(value(mid)) == k ? good : bad) = mid;
    }
    add_to_bucket(x, good + 1 - i);
    i = good + 1;
  }
  const double last = value(n - 1);
  seen_.note(std::min(first, last), std::max(first, last), n);
}

double LogHistogram::value_at_rank(uint64_t rank) const {
  uint64_t seen = 0;
  // Ascending value order: most negative (largest |x| bucket) first.
  for (int32_t i = negative_.end_index() - 1; i >= negative_.first_index(); --i) {
    seen += negative_.at(i);
    if (seen > rank) return -representative(i);
  }
  seen += zero_count_;
  if (seen > rank) return 0.0;
  for (int32_t i = positive_.first_index(); i < positive_.end_index(); ++i) {
    seen += positive_.at(i);
    if (seen > rank) return representative(i);
  }
  return seen_.max;  // unreachable while counts add up to seen_.count
}

double LogHistogram::quantile(double q) const {
  if (seen_.count == 0) {
    nearest_rank_index(q, 1);  // still reject a bad q loudly
    return 0.0;
  }
  // The extreme ranks are the tracked extremes, so q = 0 and q = 1 are exact.
  const uint64_t rank = nearest_rank_index(q, seen_.count);
  if (rank == 0) return seen_.min;
  if (rank == seen_.count - 1) return seen_.max;
  return std::clamp(value_at_rank(rank), seen_.min, seen_.max);
}

void LogHistogram::merge(const LogHistogram& other) {
  if (other.relative_error_ != relative_error_ || other.min_positive_ != min_positive_) {
    throw std::invalid_argument(
        "LogHistogram::merge: histograms differ in relative_error or min_positive; "
        "build both with the same parameters");
  }
  if (other.seen_.count == 0) return;
  for (int32_t i = other.positive_.first_index(); i < other.positive_.end_index(); ++i) {
    if (const uint64_t c = other.positive_.at(i); c > 0) positive_.add(i, c);
  }
  for (int32_t i = other.negative_.first_index(); i < other.negative_.end_index(); ++i) {
    if (const uint64_t c = other.negative_.at(i); c > 0) negative_.add(i, c);
  }
  zero_count_ += other.zero_count_;
  seen_.note(other.seen_.min, other.seen_.max, other.seen_.count);
}

std::vector<std::pair<double, uint64_t>> LogHistogram::buckets() const {
  std::vector<std::pair<double, uint64_t>> out;
  for (int32_t i = negative_.end_index() - 1; i >= negative_.first_index(); --i) {
    if (const uint64_t c = negative_.at(i); c > 0) out.emplace_back(-representative(i), c);
  }
  if (zero_count_ > 0) out.emplace_back(0.0, zero_count_);
  for (int32_t i = positive_.first_index(); i < positive_.end_index(); ++i) {
    if (const uint64_t c = positive_.at(i); c > 0) out.emplace_back(representative(i), c);
  }
  return out;
}

}  // namespace latsim::stats
