#include "latsim/pxpl5/workload.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace latsim::pxpl5 {

BinCounts::BinCounts(int processors, int regions)
    : processors_(processors),
      regions_(regions),
      counts_(static_cast<std::size_t>(processors) * regions, 0),
      triangles_(processors, 0),
      on_screen_(processors, 0) {
  if (processors <= 0 || regions <= 0) throw std::invalid_argument("BinCounts: need processors and regions");
}

BinCounts BinCounts::distribute(const Workload& w, int processors, int regions, des::RandomStream& stream) {
  BinCounts b(processors, regions);
  const double whole = std::floor(w.regions_per_triangle);
  const double fraction = w.regions_per_triangle - whole;
  for (int64_t t = 0; t < w.triangles; ++t) {
    const int p = static_cast<int>(t % processors);
    ++b.triangles_[p];
    ++b.on_screen_[p];
    int covered = static_cast<int>(whole) + (fraction > 0.0 && stream.bernoulli(fraction) ? 1 : 0);
    covered = std::clamp(covered, 1, regions);
    const int first = static_cast<int>(stream.uniform_int(static_cast<uint64_t>(regions)));
    for (int k = 0; k < covered; ++k) ++b.counts_[b.index(p, (first + k) % regions)];
  }
  return b;
}

void BinCounts::add_triangle(int64_t t, bool on_screen, const std::vector<int>& regions) {
  const int p = static_cast<int>(t % processors_);
  ++triangles_[p];
  if (!on_screen) return;
  ++on_screen_[p];
  for (int r : regions) ++counts_[index(p, r)];
}

void BinCounts::add_sphere(int64_t t, bool on_screen, const std::vector<int>& regions) {
  if (spheres_.empty()) {
    sphere_counts_.assign(counts_.size(), 0);
    spheres_.assign(static_cast<std::size_t>(processors_), 0);
    spheres_on_screen_.assign(static_cast<std::size_t>(processors_), 0);
  }
  const int p = static_cast<int>(t % processors_);
  ++spheres_[p];
  if (!on_screen) return;
  ++spheres_on_screen_[p];
  for (int r : regions) {
    ++counts_[index(p, r)];
    ++sphere_counts_[index(p, r)];
  }
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

SyntheticWorkload::SyntheticWorkload(Workload workload, int regions, des::RandomStream stream)
    : w_(workload), regions_(regions), stream_(std::move(stream)) {
  if (w_.triangles < 0) throw std::invalid_argument("a negative triangle count");
}

// The bins are drawn once per processor count: a synthetic scene is static,
// so every image bins the same, whatever the pose.
const EyeWork& SyntheticWorkload::work(int64_t, int eye, int processors) {
  if (processors != cached_processors_) {
    cached_.clear();
    for (int e = 0; e < 2; ++e) {
      des::RandomStream eye_stream = stream_.substream(e == 0 ? "left" : "right");
      EyeWork w;
      w.bins = BinCounts::distribute(w_, processors, regions_, eye_stream);
      w.on_screen_count = w_.triangles;
      cached_.push_back(std::move(w));
    }
    cached_processors_ = processors;
  }
  return cached_.at(static_cast<std::size_t>(eye));
}

}  // namespace latsim::pxpl5
