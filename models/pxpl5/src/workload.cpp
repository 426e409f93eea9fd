#include "latsim/pxpl5/workload.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace latsim::pxpl5 {

BinCounts::BinCounts(int processors, int regions)
    : processors_(processors),
      regions_(regions),
      counts_(static_cast<std::size_t>(processors) * regions, 0),
      triangles_(processors, 0) {
  if (processors <= 0 || regions <= 0) throw std::invalid_argument("BinCounts: need processors and regions");
}

BinCounts BinCounts::distribute(const Workload& w, int processors, int regions, des::RandomStream& stream) {
  BinCounts b(processors, regions);
  const double whole = std::floor(w.regions_per_triangle);
  const double fraction = w.regions_per_triangle - whole;
  for (int64_t t = 0; t < w.triangles; ++t) {
    const int p = static_cast<int>(t % processors);
    ++b.triangles_[p];
    int covered = static_cast<int>(whole) + (fraction > 0.0 && stream.bernoulli(fraction) ? 1 : 0);
    covered = std::clamp(covered, 1, regions);
    const int first = static_cast<int>(stream.uniform_int(static_cast<uint64_t>(regions)));
    for (int k = 0; k < covered; ++k) ++b.counts_[b.index(p, (first + k) % regions)];
  }
  return b;
}

int64_t BinCounts::region_commands(int region) const {
  int64_t n = 0;
  for (int p = 0; p < processors_; ++p) n += commands(p, region);
  return n;
}

int64_t BinCounts::bin_entries(int processor) const {
  int64_t n = 0;
  for (int r = 0; r < regions_; ++r) n += commands(processor, r);
  return n;
}

}  // namespace latsim::pxpl5
