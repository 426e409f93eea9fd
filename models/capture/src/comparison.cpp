#include "latsim/capture/comparison.hpp"

#include <algorithm>
#include <cmath>

namespace latsim::capture {

double percentile_sorted(const std::vector<double>& s, double q) {
  const double rank = q / 100.0 * static_cast<double>(s.size() - 1);
  const auto low = static_cast<size_t>(std::floor(rank));
  if (low + 1 >= s.size()) return s.back();
  return s[low] + (s[low + 1] - s[low]) * (rank - static_cast<double>(low));
}

SampleStats sample_stats(std::vector<double> v) {
  SampleStats s;
  s.count = static_cast<int64_t>(v.size());
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  // Neumaier's compensated sum: the mean of a long capture to the last bit it can have.
  double sum = 0.0, c = 0.0;
  for (const double x : v) {
    const double t = sum + x;
    c += std::fabs(sum) >= std::fabs(x) ? (sum - t) + x : (x - t) + sum;
    sum = t;
  }
  s.mean = (sum + c) / static_cast<double>(v.size());
  s.p50 = percentile_sorted(v, 50.0);
  s.p99 = percentile_sorted(v, 99.0);
  s.min = v.front();
  s.max = v.back();
  return s;
}

std::optional<double> ks_distance(std::vector<double> a, std::vector<double> b) {
  if (a.empty() || b.empty()) return std::nullopt;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  const double n = static_cast<double>(a.size()), m = static_cast<double>(b.size());
  // Walk both sorted samples; the CDFs change only at sample points, and at
  // a tie both steps are taken before the difference is measured.
  size_t i = 0, j = 0;
  double d = 0.0;
  while (i < a.size() || j < b.size()) {
    const double x = j >= b.size() || (i < a.size() && a[i] <= b[j]) ? a[i] : b[j];
    while (i < a.size() && a[i] == x) ++i;
    while (j < b.size() && b[j] == x) ++j;
    d = std::max(d, std::fabs(static_cast<double>(i) / n - static_cast<double>(j) / m));
  }
  return d;
}

}  // namespace latsim::capture
