// The primitive workload of a frame and how binitizing spreads it over regions.
#pragma once

#include <cstdint>
#include <vector>

#include "latsim/des/random.hpp"

namespace latsim::pxpl5 {

/// How many triangles a frame draws and how many regions each touches (per eye).
struct Workload {
  int64_t triangles = 100;
  double regions_per_triangle = 1.3;  ///< typical 1.3; 20 means every triangle covers a 640x480 screen
};

/// One eye's bins: commands each graphics processor holds for each region.
class BinCounts {
 public:
  BinCounts(int processors, int regions);

  /// Triangles are dealt round-robin to the processors (their display lists);
  /// each touches floor(r) or ceil(r) regions (r = regions_per_triangle, the
  /// fraction as a probability) as a run of consecutive regions from a random
  /// start, wrapping, so the mean coverage is r and a triangle touching every
  /// region lands in every bin. The stream is the only source of variation.
  static BinCounts distribute(const Workload& w, int processors, int regions, des::RandomStream& stream);

  int processors() const { return processors_; }
  int regions() const { return regions_; }
  int64_t commands(int processor, int region) const { return counts_[index(processor, region)]; }
  int64_t region_commands(int region) const;
  int64_t triangles(int processor) const { return triangles_[processor]; }
  /// Bin entries a processor writes (sum over regions): its binitize work.
  int64_t bin_entries(int processor) const;

 private:
  std::size_t index(int p, int r) const { return static_cast<std::size_t>(p) * regions_ + r; }

  int processors_;
  int regions_;
  std::vector<int64_t> counts_;
  std::vector<int64_t> triangles_;
};

}  // namespace latsim::pxpl5
