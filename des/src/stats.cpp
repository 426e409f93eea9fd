#include "latsim/des/stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace latsim::des {

namespace {

void require_finite(double x, const char* where) {
  if (!std::isfinite(x)) {
    throw std::invalid_argument(std::string(where) + ": sample is " + std::to_string(x) +
                                "; a model emitted a non-finite value, which is a bug in that model");
  }
}

}  // namespace

uint64_t nearest_rank_index(double q, uint64_t n) {
  if (!(q >= 0.0 && q <= 1.0)) {
    throw std::invalid_argument("quantile: q must be in [0, 1], got " + std::to_string(q));
  }
  if (n == 0) throw std::invalid_argument("quantile: no values");
  const double rank = std::ceil(q * static_cast<double>(n));
  if (rank <= 1.0) return 0;
  const auto k = static_cast<uint64_t>(rank) - 1;
  return std::min(k, n - 1);
}

// ---------------------------------------------------------------- RunningStats

void RunningStats::add(double x) {
  require_finite(x, "RunningStats::add");
  ++count_;
  if (count_ == 1) {
    shift_ = x;
    mean_ = 0.0;
    m2_ = 0.0;
    min_ = x;
    max_ = x;
    return;
  }
  const double delta = (x - shift_) - mean_;
  mean_ += delta / static_cast<double>(count_);
  m2_ += delta * ((x - shift_) - mean_);
  min_ = std::min(min_, x);
  max_ = std::max(max_, x);
}

double RunningStats::variance() const {
  return count_ < 2 ? 0.0 : m2_ / static_cast<double>(count_ - 1);
}

double RunningStats::stddev() const { return std::sqrt(variance()); }

void RunningStats::merge(const RunningStats& other) {
  if (other.count_ == 0) return;
  if (count_ == 0) {
    *this = other;
    return;
  }
  const double na = static_cast<double>(count_);
  const double nb = static_cast<double>(other.count_);
  const double n = na + nb;
  // Express the other's mean relative to this shift before combining.
  const double delta = ((other.shift_ - shift_) + other.mean_) - mean_;
  mean_ += delta * (nb / n);
  m2_ += other.m2_ + delta * delta * (na * nb / n);
  count_ += other.count_;
  min_ = std::min(min_, other.min_);
  max_ = std::max(max_, other.max_);
}

// ---------------------------------------------------------------- LogHistogram

void LogHistogram::DenseCounts::add(int32_t index, uint64_t weight) {
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
  if (!(std::isfinite(min_positive) && min_positive > 0.0)) {
    throw std::invalid_argument("LogHistogram: min_positive must be finite and > 0");
  }
  gamma_ = (1.0 + relative_error) / (1.0 - relative_error);
  log_gamma_ = std::log(gamma_);
}

int32_t LogHistogram::bucket_index(double magnitude) const {
  return static_cast<int32_t>(std::ceil(std::log(magnitude) / log_gamma_));
}

double LogHistogram::representative(int32_t index) const {
  // 2 * gamma^i / (gamma + 1) = (1 - a) * gamma^i, computed in the log domain
  // so the topmost bucket near DBL_MAX does not overflow.
  return std::exp(static_cast<double>(index) * log_gamma_ + std::log1p(-relative_error_));
}

void LogHistogram::add(double x, uint64_t weight) {
  require_finite(x, "LogHistogram::add");
  if (weight == 0) return;
  const double magnitude = std::fabs(x);
  if (magnitude < min_positive_) {
    zero_count_ += weight;
  } else if (x > 0.0) {
    positive_.add(bucket_index(magnitude), weight);
  } else {
    negative_.add(bucket_index(magnitude), weight);
  }
  if (count_ == 0) {
    min_ = x;
    max_ = x;
  } else {
    min_ = std::min(min_, x);
    max_ = std::max(max_, x);
  }
  count_ += weight;
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
  return max_;  // unreachable while counts add up to count_
}

double LogHistogram::quantile(double q) const {
  if (count_ == 0) {
    nearest_rank_index(q, 1);  // still reject a bad q loudly
    return 0.0;
  }
  // The extreme ranks are the tracked extremes, so q = 0 and q = 1 are exact.
  const uint64_t rank = nearest_rank_index(q, count_);
  if (rank == 0) return min_;
  if (rank == count_ - 1) return max_;
  return std::clamp(value_at_rank(rank), min_, max_);
}

void LogHistogram::merge(const LogHistogram& other) {
  if (other.relative_error_ != relative_error_ || other.min_positive_ != min_positive_) {
    throw std::invalid_argument(
        "LogHistogram::merge: histograms differ in relative_error or min_positive; "
        "build both with the same parameters");
  }
  if (other.count_ == 0) return;
  for (int32_t i = other.positive_.first_index(); i < other.positive_.end_index(); ++i) {
    if (const uint64_t c = other.positive_.at(i); c > 0) positive_.add(i, c);
  }
  for (int32_t i = other.negative_.first_index(); i < other.negative_.end_index(); ++i) {
    if (const uint64_t c = other.negative_.at(i); c > 0) negative_.add(i, c);
  }
  zero_count_ += other.zero_count_;
  if (count_ == 0) {
    min_ = other.min_;
    max_ = other.max_;
  } else {
    min_ = std::min(min_, other.min_);
    max_ = std::max(max_, other.max_);
  }
  count_ += other.count_;
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

// ---------------------------------------------------------------- Distribution

Distribution::Distribution(double relative_error, bool keep_samples, size_t max_samples)
    : histogram_(relative_error), keep_samples_(keep_samples), max_samples_(max_samples) {}

void Distribution::add(double x) {
  stats_.add(x);  // rejects non-finite input before anything changes
  histogram_.add(x);
  if (!keep_samples_) return;
  if (samples_.size() < max_samples_) {
    samples_.push_back(x);
  } else {
    release_samples();
  }
}

void Distribution::release_samples() {
  keep_samples_ = false;
  std::vector<double>().swap(samples_);  // give the memory back, not just clear()
}

double Distribution::quantile(double q) const {
  if (!keep_samples_) return histogram_.quantile(q);
  if (samples_.empty()) {
    nearest_rank_index(q, 1);  // reject a bad q even when empty
    return 0.0;
  }
  std::vector<double> work = samples_;
  const auto k = static_cast<std::ptrdiff_t>(nearest_rank_index(q, work.size()));
  std::nth_element(work.begin(), work.begin() + k, work.end());
  return work[static_cast<size_t>(k)];
}

void Distribution::merge(const Distribution& other) {
  histogram_.merge(other.histogram_);  // throws on mismatched parameters first
  stats_.merge(other.stats_);
  if (keep_samples_ && other.keep_samples_ &&
      samples_.size() + other.samples_.size() <= max_samples_) {
    samples_.insert(samples_.end(), other.samples_.begin(), other.samples_.end());
  } else if (keep_samples_) {
    release_samples();
  }
}

Distribution::Summary Distribution::summary() const {
  Summary s;
  s.count = stats_.count();
  if (s.count == 0) return s;
  s.mean = stats_.mean();
  s.stddev = stats_.stddev();
  s.min = stats_.min();
  s.max = stats_.max();
  if (keep_samples_) {
    // One sort serves all four quantiles.
    std::vector<double> sorted = samples_;
    std::sort(sorted.begin(), sorted.end());
    const auto at = [&](double q) { return sorted[nearest_rank_index(q, sorted.size())]; };
    s.p50 = at(0.5);
    s.p90 = at(0.9);
    s.p99 = at(0.99);
    s.p999 = at(0.999);
  } else {
    s.p50 = histogram_.quantile(0.5);
    s.p90 = histogram_.quantile(0.9);
    s.p99 = histogram_.quantile(0.99);
    s.p999 = histogram_.quantile(0.999);
  }
  return s;
}

std::vector<std::pair<double, uint64_t>> Distribution::plot_histogram(int bins) const {
  if (bins < 1) {
    throw std::invalid_argument("Distribution::plot_histogram: bins must be >= 1, got " +
                                std::to_string(bins));
  }
  std::vector<std::pair<double, uint64_t>> out;
  if (count() == 0) return out;
  const double lo = stats_.min();
  const double hi = stats_.max();
  if (!(hi > lo)) {
    out.emplace_back(lo, count());
    return out;
  }
  const auto n_bins = static_cast<size_t>(bins);
  const double width = (hi - lo) / static_cast<double>(bins);
  out.reserve(n_bins);
  for (size_t b = 0; b < n_bins; ++b) {
    out.emplace_back(lo + width * static_cast<double>(b), 0);
  }
  const auto bin_of = [&](double v) {
    // Representatives may lie just outside [min, max]; clamp them to the ends.
    const double pos = (std::clamp(v, lo, hi) - lo) / width;
    return std::min(static_cast<size_t>(pos), n_bins - 1);
  };
  if (keep_samples_) {
    for (const double v : samples_) ++out[bin_of(v)].second;
  } else {
    for (const auto& [value, c] : histogram_.buckets()) out[bin_of(value)].second += c;
  }
  return out;
}

}  // namespace latsim::des
