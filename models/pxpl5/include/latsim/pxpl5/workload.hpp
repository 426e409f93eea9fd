// The primitive workload of an image: which triangles are on screen and how
// binitizing spreads them over the renderer regions.
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

/// One eye's bins: commands each graphics processor holds for each region,
/// triangles' and spheres' (a sphere command is a primitive of its own on
/// the ring and in the renderers).
class BinCounts {
 public:
  BinCounts() = default;
  BinCounts(int processors, int regions);

  /// Triangles are dealt round-robin to the processors (their display lists);
  /// each touches floor(r) or ceil(r) regions (r = regions_per_triangle, the
  /// fraction as a probability) as a run of consecutive regions from a random
  /// start, wrapping, so the mean coverage is r and a triangle touching every
  /// region lands in every bin. The stream is the only source of variation.
  static BinCounts distribute(const Workload& w, int processors, int regions, des::RandomStream& stream);

  int processors() const { return processors_; }
  int regions() const { return regions_; }
  /// Commands of every kind.
  int64_t commands(int processor, int region) const { return counts_[index(processor, region)]; }
  /// Of those, the spheres' (the rest are triangles').
  int64_t sphere_commands(int processor, int region) const {
    return sphere_counts_.empty() ? 0 : sphere_counts_[index(processor, region)];
  }
  int64_t region_commands(int region) const;
  /// Triangles in a processor's display list (on screen or not).
  int64_t triangles(int processor) const { return triangles_[processor]; }
  /// Of those, the ones inside the eye's view (the rest are transformed and rejected).
  int64_t on_screen(int processor) const { return on_screen_[processor]; }
  /// Spheres in a processor's display list, and those inside the eye's view.
  int64_t spheres(int processor) const { return spheres_.empty() ? 0 : spheres_[processor]; }
  int64_t spheres_on_screen(int processor) const { return spheres_.empty() ? 0 : spheres_on_screen_[processor]; }
  /// Bin entries a processor writes (sum over regions, every kind): its binitize work.
  int64_t bin_entries(int processor) const;

  /// Deals display-list triangle `t` (round-robin) and, when `on_screen`, one
  /// command into each region of `regions` (no region twice).
  void add_triangle(int64_t t, bool on_screen, const std::vector<int>& regions);
  /// The same for a sphere at display-list position `t` (after the triangles).
  void add_sphere(int64_t t, bool on_screen, const std::vector<int>& regions);

 private:
  std::size_t index(int p, int r) const { return static_cast<std::size_t>(p) * regions_ + r; }

  int processors_ = 0;
  int regions_ = 0;
  std::vector<int64_t> counts_;
  std::vector<int64_t> triangles_;
  std::vector<int64_t> on_screen_;
  // Allocated by the first sphere: a triangle-only list costs nothing more.
  std::vector<int64_t> sphere_counts_;
  std::vector<int64_t> spheres_;
  std::vector<int64_t> spheres_on_screen_;
};

/// What one eye's image costs: its bins and, in display-list order, which
/// triangles lie inside the eye's view.
struct EyeWork {
  BinCounts bins;
  std::vector<uint8_t> on_screen;  ///< 1 per display-list triangle inside the view; empty: all are
  int64_t on_screen_count = 0;
  int64_t spheres_on_screen_count = 0;
};

/// Where each image's work comes from: a fixed synthetic load, or the scene as
/// seen from the pose the image is computed with.
class WorkloadSource {
 public:
  virtual ~WorkloadSource() = default;
  /// Length of the display list (every triangle the processors transform).
  virtual int64_t triangles() const = 0;
  /// Spheres the display list holds after its triangles.
  virtual int64_t spheres() const { return 0; }
  /// The work of `eye`'s image computed from host sample `sample_token` (-1
  /// before the first sample: the application's starting view), binned for
  /// `processors` display lists. Valid until the next call.
  virtual const EyeWork& work(int64_t sample_token, int eye, int processors) = 0;
};

/// The calibration load: `triangles` on-screen triangles spread over regions by
/// BinCounts::distribute, the same for every image (each eye its own substream).
class SyntheticWorkload final : public WorkloadSource {
 public:
  SyntheticWorkload(Workload workload, int regions, des::RandomStream stream);
  int64_t triangles() const override { return w_.triangles; }
  const EyeWork& work(int64_t sample_token, int eye, int processors) override;

 private:
  Workload w_;
  int regions_;
  des::RandomStream stream_;
  std::vector<EyeWork> cached_;  // per eye, for cached_processors_
  int cached_processors_ = 0;
};

}  // namespace latsim::pxpl5
