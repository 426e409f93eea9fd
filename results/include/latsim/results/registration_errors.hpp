// Registration error: where world points are drawn in each shown image, and
// how far from where they are seen when their pixels light up.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "latsim/display/display.hpp"
#include "latsim/display/persistence.hpp"
#include "latsim/display/raster_timing.hpp"
#include "latsim/results/figure_writer.hpp"
#include "latsim/results/phase_split.hpp"
#include "latsim/tracker/motion_source.hpp"

namespace latsim::results {

/// Where a probe point is drawn versus where it belongs, per lit field.
struct ProbeSet {
  std::vector<glm::dvec3> points_m;  ///< world points
  double hfov_deg = 90.0;            ///< display field of view (for pixels and visibility)
};

/// Turns every probe a span lights, and every world point a frameless pixel
/// shows, into registration_error_arcmin and registration_error_px (split by
/// motion phase when the run asks).
class RegistrationErrors {
 public:
  RegistrationErrors(FigureWriter figures, const tracker::MotionSource& motion, const display::RasterTiming& timing,
                     ProbeSet probes, double ipd_m, bool stereo);

  /// Judges a probe at the middle of its pixel's lit interval (nullptr: at its scanout instant).
  void set_persistence(const display::Persistence* persistence) { persistence_ = persistence; }
  void split_by(MotionPhases* phases) { phases_ = phases; }
  bool has_probes() const { return !probes_.points_m.empty(); }

  /// Registration error of world point `point_m`, drawn along head-frame
  /// direction `drawn_head_dir` of eye `eye`, lit at `photon`.
  void point_drawn(int eye, const glm::dvec3& point_m, const glm::dvec3& drawn_head_dir, des::Time photon);
  /// The probes lit by a span, drawn with `orientation` (from sample
  /// `sample_index`, or the image's own when image_pose) and `position_m`.
  void probes_lit(const display::ScanoutSpan& span, const glm::dquat& orientation, const glm::dvec3& position_m,
                  int64_t sample_index, int64_t image_id, bool image_pose);
  /// Whether the span's lines light no probe of an image drawn with its own
  /// pose, known without projecting.
  bool no_probe_on(const display::ScanoutSpan& span) const {
    // Most spans (one line each at line fidelity) show no probe: with the
    // image's hits indexed by line, that takes two loads.
    const ProbeCache& cache = cache_[span.eye & 1];
    return cache.image_pose && cache.image_id == span.image_id && cache.field == span.field &&
           !cache.first_hit.empty() && span.line >= 0 && span.line_end <= timing_.lines_per_field() &&
           cache.first_hit[static_cast<size_t>(span.line)] == cache.first_hit[static_cast<size_t>(span.line_end)];
  }

 private:
  struct ProbeHit {
    int line;
    double x_px;
    size_t probe;
    bool operator<(const ProbeHit& o) const { return line < o.line; }
  };
  struct ProbeCache {
    int64_t image_id = -2;
    int64_t field = -1;
    bool image_pose = false;  ///< projected with the image's own pose (sample_index and orientation unused)
    int64_t sample_index = -1;
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  ///< the drawn orientation the hits were projected with
    std::vector<ProbeHit> hits;                   ///< sorted by line
    std::vector<size_t> first_hit;                ///< per line of the field (and one past): its first hit
    int lookups = 0;                              ///< spans served before first_hit was built
  };

  void project(ProbeCache& cache, const display::ScanoutSpan& span, const glm::dquat& orientation,
               const glm::dvec3& position_m) const;

  FigureWriter figures_;
  const tracker::MotionSource& motion_;
  const display::RasterTiming& timing_;
  ProbeSet probes_;
  double ipd_m_;
  bool stereo_;
  double rad_per_px_ = 0.0;
  double tan_half_h_ = 1.0, tan_half_v_ = 1.0;
  const display::Persistence* persistence_ = nullptr;
  MotionPhases* phases_ = nullptr;
  ProbeCache cache_[2];
  stats::Distribution* arcmin_ = nullptr;
  stats::Distribution* px_ = nullptr;
  PhaseSplit split_{"registration_error_arcmin"};
};

}  // namespace latsim::results
