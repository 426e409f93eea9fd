// Registration error: where the probes are drawn in each shown image, and
// how far from where they are seen when their pixels light up.
#include <algorithm>
#include <cmath>

#include "latsim/results/latency_recorder.hpp"
#include "latsim/units/units.hpp"

namespace latsim::results {

namespace {


// Angle between two directions, stable for tiny and for near-opposite angles.
double angle_between_dirs(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

}  // namespace

void LatencyRecorder::registration(int eye, const glm::dvec3& point_m, const glm::dvec3& drawn_head_dir,
                                   des::Time photon) {
  const tracker::Pose truth = tracker::eye_pose(motion_.pose_at(photon), eye, ipd_m_, stereo_);
  const glm::dvec3 seen = truth.orientation * drawn_head_dir;
  const glm::dvec3 should = glm::normalize(point_m - truth.position_m);
  const double angle = angle_between_dirs(seen, should);
  const double arcmin = units::rad_to_deg(angle) * units::kArcminPerDeg;
  record(reg_arcmin_, "registration_error_arcmin", arcmin);
  record(reg_px_, "registration_error_px", angle / rad_per_px_);
  add_split(reg_split_, "registration_error_arcmin", arcmin, photon);
}

void LatencyRecorder::record_probes(const display::ScanoutSpan& span, const glm::dquat& orientation,
                                    const glm::dvec3& position_m, int64_t sample_index, int64_t image_id,
                                    bool image_pose) {
  ProbeCache& cache = probe_cache_[span.eye & 1];
  // Predicted per line (address recalculation), the drawn orientation may
  // change from line to line even with the same sample; the image's own pose
  // is the same for every span that shows the image.
  const bool same = cache.image_id == image_id && cache.field == span.field && cache.image_pose == image_pose &&
                    (image_pose || (cache.sample_index == sample_index && cache.orientation == orientation));
  if (!same) {
    // Where each probe is drawn in this image: project with the drawn pose.
    cache.image_id = image_id;
    cache.field = span.field;
    cache.image_pose = image_pose;
    cache.sample_index = sample_index;
    cache.orientation = orientation;
    cache.hits.clear();
    const glm::dquat inv = glm::conjugate(orientation);
    const int w = timing_.params().width_px, h = timing_.params().height_px;
    for (size_t i = 0; i < probes_.points_m.size(); ++i) {
      const glm::dvec3 d = inv * (probes_.points_m[i] - position_m);
      if (d.z >= -1e-9) continue;  // behind the eye
      const double u = (d.x / -d.z) / tan_half_h_, v = (d.y / -d.z) / tan_half_v_;
      const double x = (u + 1.0) * 0.5 * w, y = (1.0 - v) * 0.5 * h;
      if (x < 0 || x >= w || y < 0 || y >= h) continue;
      // Interlaced: a probe is lit by the nearest row of this field's parity.
      const int row = static_cast<int>(std::floor(y));
      int line = timing_.line_of_row(span.field, row);
      if (line < 0) line = timing_.line_of_row(span.field, row + 1 < h ? row + 1 : row - 1);
      cache.hits.push_back({line, x, i});
    }
    std::stable_sort(cache.hits.begin(), cache.hits.end());
    cache.first_hit.clear();
    cache.lookups = 0;
  }
  // The hits on the span's lines (several at field fidelity): by binary
  // search, or once the hits serve a second span (a span per line at line
  // fidelity) from an index of where each line's hits begin.
  const int lines = timing_.lines_per_field();
  if (cache.first_hit.empty() && ++cache.lookups >= 2) {
    cache.first_hit.assign(static_cast<size_t>(lines) + 1, 0);
    size_t k = 0;
    for (int line = 0; line <= lines; ++line) {
      while (k < cache.hits.size() && cache.hits[k].line < line) ++k;
      cache.first_hit[static_cast<size_t>(line)] = k;
    }
  }
  auto first = cache.hits.begin(), last = cache.hits.end();
  if (!cache.first_hit.empty() && span.line >= 0 && span.line_end <= lines) {
    first += static_cast<std::ptrdiff_t>(cache.first_hit[static_cast<size_t>(span.line)]);
    last = cache.hits.begin() + static_cast<std::ptrdiff_t>(cache.first_hit[static_cast<size_t>(span.line_end)]);
  } else {
    first = std::lower_bound(cache.hits.begin(), cache.hits.end(), ProbeHit{span.line, 0.0, 0});
    last = std::lower_bound(first, cache.hits.end(), ProbeHit{span.line_end, 0.0, 0});
  }
  for (auto h = first; h != last; ++h) {
    const int xi = static_cast<int>(h->x_px);
    if (xi < span.x_begin || xi >= span.x_end) continue;
    const glm::dvec3 p = probes_.points_m[h->probe];
    const glm::dvec3 drawn_head_dir = glm::conjugate(orientation) * glm::normalize(p - position_m);
    // Judged at the middle of the pixel's lit interval on a display with persistence.
    des::Time t = timing_.pixel_time(span.field, h->line, xi);
    if (persistence_) t = persistence_->lit(span.field, t).middle();
    registration(span.eye, p, drawn_head_dir, t);
  }
}

}  // namespace latsim::results
