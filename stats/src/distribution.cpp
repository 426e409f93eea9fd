#include <algorithm>
#include <stdexcept>
#include <string>

#include "latsim/stats/stats.hpp"

namespace latsim::stats {

Distribution::Distribution(double relative_error, bool keep_samples, size_t max_samples)
    : histogram_(relative_error), keep_samples_(keep_samples), max_samples_(max_samples) {}

void Distribution::check_kind(Kind kind) const {
  if (kind_ == kind || kind_ == Kind::empty || kind == Kind::empty) [[likely]] return;
  throw std::logic_error(kind == Kind::durations
                               ? "Distribution: a duration added to a distribution of plain numbers; add the "
                                 "same kind of value to one name throughout"
                               : "Distribution: a plain number added to a distribution of durations; add a "
                                 "des::Time instead");
}

void Distribution::keep(double stored_value) {
  if (samples_.size() < max_samples_) {
    samples_.push_back(stored_value);
  } else {
    release_samples();
  }
}

void Distribution::add(double x) {
  check_kind(Kind::plain);
  stats_.add(x);  // rejects non-finite input before anything changes
  kind_ = Kind::plain;
  histogram_.add(x);
  if (keep_samples_) keep(x);
}

void Distribution::add_run(const TickRun& run) {
  if (run.count == 0) return;
  check_kind(Kind::durations);
  kind_ = Kind::durations;
  stats_.add_run(run);
  add_run_samples(run);
}

void Distribution::add_run(const TickRun& run, const TickRunSums& sums) {
  if (run.count == 0) return;
  check_kind(Kind::durations);
  kind_ = Kind::durations;
  stats_.add_run(run, sums);
  add_run_samples(run);
}

void Distribution::add_run(const TickRunSums& sums, const RunBuckets& b, const TickRunMoments& moments) {
  if (b.run.count == 0) return;
  check_kind(Kind::durations);
  histogram_.add_buckets(b);  // throws on a bucket shape of another histogram first
  kind_ = Kind::durations;
  stats_.add_run(b.run, sums, b.last, moments);
  add_kept_samples(b.run);
}

void Distribution::add_run_samples(const TickRun& run) {
  histogram_.add_run(run);
  add_kept_samples(run);
}

void Distribution::add_kept_samples(const TickRun& run) {
  if (!keep_samples_) return;
  TickStepper t(run);
  for (uint64_t i = 0; i < run.count && keep_samples_; ++i, t.step()) keep(static_cast<double>(t.ticks()));
}

void Distribution::add_arithmetic_run(double first, double step, uint64_t n) {
  if (n == 0) return;
  check_kind(Kind::plain);
  stats_.add_arithmetic_run(first, step, n);  // validates before anything changes
  kind_ = Kind::plain;
  histogram_.add_arithmetic_run(first, step, n);
  for (uint64_t i = 0; i < n && keep_samples_; ++i) keep(first + static_cast<double>(i) * step);
}

void Distribution::release_samples() {
  keep_samples_ = false;
  std::vector<double>().swap(samples_);  // give the memory back, not just clear()
}

double Distribution::quantile(double q) const {
  if (!keep_samples_) return histogram_.quantile(q) * unit();
  if (samples_.empty()) {
    nearest_rank_index(q, 1);  // reject a bad q even when empty
    return 0.0;
  }
  std::vector<double> work = samples_;
  const auto k = static_cast<std::ptrdiff_t>(nearest_rank_index(q, work.size()));
  std::nth_element(work.begin(), work.begin() + k, work.end());
  return work[static_cast<size_t>(k)] * unit();
}

void Distribution::merge(const Distribution& other) {
  check_kind(other.kind_);
  histogram_.merge(other.histogram_);  // throws on mismatched parameters first
  if (other.kind_ != Kind::empty) kind_ = other.kind_;
  stats_.merge(other.stats_);
  if (keep_samples_ && other.keep_samples_ && samples_.size() + other.samples_.size() <= max_samples_) {
    samples_.insert(samples_.end(), other.samples_.begin(), other.samples_.end());
  } else if (keep_samples_) {
    release_samples();
  }
}

Distribution::Summary Distribution::summary() const {
  Summary s;
  s.count = stats_.count();
  if (s.count == 0) return s;
  const double u = unit();
  s.mean = stats_.mean() * u;
  s.stddev = stats_.stddev() * u;
  s.min = stats_.min() * u;
  s.max = stats_.max() * u;
  if (keep_samples_) {
    // One sort serves all four quantiles.
    std::vector<double> sorted = samples_;
    std::sort(sorted.begin(), sorted.end());
    const auto at = [&](double q) { return sorted[nearest_rank_index(q, sorted.size())] * u; };
    s.p50 = at(0.5);
    s.p90 = at(0.9);
    s.p99 = at(0.99);
    s.p999 = at(0.999);
  } else {
    s.p50 = histogram_.quantile(0.5) * u;
    s.p90 = histogram_.quantile(0.9) * u;
    s.p99 = histogram_.quantile(0.99) * u;
    s.p999 = histogram_.quantile(0.999) * u;
  }
  return s;
}

std::vector<std::pair<double, uint64_t>> Distribution::plot_histogram(int bins) const {
  if (bins < 1) {
    throw std::invalid_argument("Distribution::plot_histogram: bins must be >= 1, got " + std::to_string(bins));
  }
  std::vector<std::pair<double, uint64_t>> out;
  if (count() == 0) return out;
  const double u = unit();
  const double lo = stats_.min() * u;
  const double hi = stats_.max() * u;
  if (!(hi > lo)) {
    out.emplace_back(lo, count());
    return out;
  }
  const auto n_bins = static_cast<size_t>(bins);
  const double width = (hi - lo) / static_cast<double>(bins);
  out.reserve(n_bins);
  for (size_t b = 0; b < n_bins; ++b) out.emplace_back(lo + width * static_cast<double>(b), 0);
  const auto bin_of = [&](double stored) {
    // Representatives may lie just outside [min, max]; clamp them to the ends.
    const double pos = (std::clamp(stored * u, lo, hi) - lo) / width;
    return std::min(static_cast<size_t>(pos), n_bins - 1);
  };
  if (keep_samples_) {
    for (const double v : samples_) ++out[bin_of(v)].second;
  } else {
    for (const auto& [value, c] : histogram_.buckets()) out[bin_of(value)].second += c;
  }
  return out;
}

}  // namespace latsim::stats
