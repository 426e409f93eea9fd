#include "latsim/pipelines/latency_recorder.hpp"

#include <algorithm>
#include <cmath>

namespace latsim::pipelines {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Angle between two directions, stable for tiny and for near-opposite angles.
double angle_between_dirs(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

}  // namespace

tracker::Pose eye_pose_of(const tracker::Pose& head, int eye, double ipd_m, bool stereo) {
  if (!stereo) return head;
  const double offset = (eye == 0 ? -0.5 : 0.5) * ipd_m;
  tracker::Pose p = head;
  p.position_m += head.orientation * glm::dvec3(offset, 0.0, 0.0);
  return p;
}

LatencyRecorder::LatencyRecorder(const des::Simulator& sim, const tracker::MotionSource& motion, const HostFeed& host,
                                 const display::RasterTiming& timing, ProbeSet probes, double ipd_m, bool stereo,
                                 bool keep_samples)
    : sim_(sim),
      motion_(motion),
      host_(host),
      timing_(timing),
      probes_(std::move(probes)),
      ipd_m_(ipd_m),
      stereo_(stereo),
      keep_samples_(keep_samples) {
  const double w = timing_.params().width_px, h = timing_.params().height_px;
  tan_half_h_ = std::tan(probes_.hfov_deg * kPi / 360.0);
  tan_half_v_ = tan_half_h_ * h / w;
  // Pixels per radian at the image centre of a pinhole display.
  rad_per_px_ = 2.0 * tan_half_h_ / w;
}

int64_t LatencyRecorder::register_image(const ImageRecord& record) {
  const int64_t id = next_id_++;
  images_.emplace(id, Held{record, false});
  return id;
}

const ImageRecord* LatencyRecorder::image(int64_t id) const {
  auto it = images_.find(id);
  return it == images_.end() ? nullptr : &it->second.record;
}

des::Distribution& LatencyRecorder::distribution_ref(const std::string& name) {
  auto it = dists_.find(name);
  if (it == dists_.end()) it = dists_.emplace(name, des::Distribution(0.005, keep_samples_)).first;
  return it->second;
}

void LatencyRecorder::add(const std::string& name, double value) {
  distribution_ref(name).add(value);
  if (sample_log_on_) sample_log_.push_back({sim_.now().to_ms(), name, value});
}

void LatencyRecorder::add_to(des::Distribution* d, const char* name, double value) {
  d->add(value);
  if (sample_log_on_) sample_log_.push_back({sim_.now().to_ms(), name, value});
}

void LatencyRecorder::count(const std::string& name, int64_t n) { counters_[name] += n; }

const des::Distribution* LatencyRecorder::distribution(const std::string& name) const {
  auto it = dists_.find(name);
  return it == dists_.end() ? nullptr : &it->second;
}

int64_t LatencyRecorder::counter(const std::string& name) const {
  auto it = counters_.find(name);
  return it == counters_.end() ? 0 : it->second;
}

void LatencyRecorder::prune(int64_t below_id) {
  while (!images_.empty() && images_.begin()->first < below_id) images_.erase(images_.begin());
}

void LatencyRecorder::on_field_start(int eye, int64_t field, des::Time) {
  if (eye == 0) count("fields");
  (void)field;
}

void LatencyRecorder::on_scanout(const display::ScanoutSpan& span) {
  auto it = images_.find(span.image_id);
  if (it == images_.end()) {
    count("unlit_spans");
    return;
  }
  Held& held = it->second;
  const ImageRecord& img = held.record;
  const des::Time photon = span.photon_time;
  if (!held.shown) {
    held.shown = true;
    first_shown(img, span);
    // Images older than one shown now (same eye) will not be shown again.
    prune(span.image_id - 64);
    it = images_.find(span.image_id);
  }

  tracker::Pose drawn = img.eye_pose;
  int64_t sample_index = img.sample.index;
  des::Time origin = img.sample.measured_at;
  if (img.orientation_at_scanout) {
    // The address recalculation pipeline looks up the newest orientation as the
    // pixel is fetched; at field fidelity the newest one at the retrace.
    const auto newest = host_.newest_at(std::min(photon, sim_.now()));
    if (newest) {
      const tracker::Pose head = newest->pose;
      drawn.orientation = eye_pose_of(head, span.eye, ipd_m_, stereo_).orientation;
      sample_index = newest->index;
      if (!rotation_) rotation_ = &distribution_ref("rotation_latency_ms");
      if (!translation_) translation_ = &distribution_ref("translation_latency_ms");
      add_to(rotation_, "rotation_latency_ms", (photon - newest->measured_at).to_ms());
      add_to(translation_, "translation_latency_ms", (photon - img.sample.measured_at).to_ms());
      origin = newest->measured_at;
    }
  } else if (img.warp == ImageRecord::Warp::rotation) [[unlikely]] {
    // Re-projected to a newer orientation; the position is the rendered one.
    if (!rotation_) rotation_ = &distribution_ref("rotation_latency_ms");
    if (!translation_) translation_ = &distribution_ref("translation_latency_ms");
    add_to(rotation_, "rotation_latency_ms", (photon - img.orientation_measured_at).to_ms());
    add_to(translation_, "translation_latency_ms", (photon - origin).to_ms());
  }
  if (!mtp_) {
    mtp_ = &distribution_ref("motion_to_photon_ms");
    display_ms_ = &distribution_ref("display_ms");
  }
  add_to(mtp_, "motion_to_photon_ms", (photon - origin).to_ms());
  if (span.field != scan_field_) {
    scan_field_ = span.field;
    scan_start_ = timing_.scanout_start(span.field);
  }
  add_to(display_ms_, "display_ms", (photon - scan_start_).to_ms());
  // Age of the shown image's input when the field starts to light up, once
  // per field and eye: the "update interval" view of latency.
  if (span.line == 0 && span.x_begin == 0) add("image_age_ms", (scan_start_ - origin).to_ms());
  if (!probes_.points_m.empty()) record_probes(span, drawn, sample_index, span.image_id);
}

void LatencyRecorder::first_shown(const ImageRecord& img, const display::ScanoutSpan& span) {
  // The image's scanout starts with the first span that shows it: line 0 of
  // the field for an image swapped in at a retrace, the line being scanned
  // for one shown at once (tearing) or written just ahead of the beam (a strip).
  const des::Time scan_start = span.written_at;
  const double render_latency_ms = (scan_start - img.render_start).to_ms();
  add("render_latency_ms", render_latency_ms);
  add("render_latency_fields", render_latency_ms / timing_.field_period_ms());
  add("tracker_to_render_ms", (img.render_start - img.sample.measured_at).to_ms());
  if (!img.continues_image) count("images_shown");
  if (!ledger_on_) return;
  const des::Time swap = timing_.field_start(span.field);
  const des::Time scan_end = timing_.line_time(span.field, timing_.lines_per_field() - 1);
  ledger_.push_back(nlohmann::json{{"frame", img.frame},
                                   {"eye", img.eye},
                                   {"field", span.field},
                                   {"sample", img.sample.index},
                                   {"measured_ps", img.sample.measured_at.ticks()},
                                   {"host_received_ps", img.host_received.ticks()},
                                   {"render_start_ps", img.render_start.ticks()},
                                   {"render_end_ps", img.render_end.ticks()},
                                   {"swap_ps", swap.ticks()},
                                   {"scanout_start_ps", scan_start.ticks()},
                                   {"scanout_end_ps", scan_end.ticks()}});
}

void LatencyRecorder::record_probes(const display::ScanoutSpan& span, const tracker::Pose& drawn,
                                    int64_t sample_index, int64_t image_id) {
  ProbeCache& cache = probe_cache_[span.eye & 1];
  if (cache.image_id != image_id || cache.field != span.field || cache.sample_index != sample_index) {
    // Where each probe is drawn in this image: project with the drawn pose.
    cache.image_id = image_id;
    cache.field = span.field;
    cache.sample_index = sample_index;
    cache.hits.clear();
    const glm::dquat inv = glm::conjugate(drawn.orientation);
    const int w = timing_.params().width_px, h = timing_.params().height_px;
    for (size_t i = 0; i < probes_.points_m.size(); ++i) {
      const glm::dvec3 d = inv * (probes_.points_m[i] - drawn.position_m);
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
  }
  const auto [first, last] = std::equal_range(cache.hits.begin(), cache.hits.end(), ProbeHit{span.line, 0.0, 0});
  for (auto h = first; h != last; ++h) {
    const ProbeHit& hit = *h;
    const int xi = static_cast<int>(hit.x_px);
    if (xi < span.x_begin || xi >= span.x_end) continue;
    des::Time t = timing_.pixel_time(span.field, span.line, xi);
    if (persistence_) t = persistence_->lit(span.field, t).middle();
    const tracker::Pose truth = eye_pose_of(motion_.pose_at(t), span.eye, ipd_m_, stereo_);
    const glm::dvec3 p = probes_.points_m[hit.probe];
    const glm::dvec3 drawn_head_dir = glm::conjugate(drawn.orientation) * glm::normalize(p - drawn.position_m);
    const glm::dvec3 seen = truth.orientation * drawn_head_dir;
    const glm::dvec3 should = glm::normalize(p - truth.position_m);
    const double angle = angle_between_dirs(seen, should);
    if (!reg_arcmin_) {
      reg_arcmin_ = &distribution_ref("registration_error_arcmin");
      reg_px_ = &distribution_ref("registration_error_px");
    }
    add_to(reg_arcmin_, "registration_error_arcmin", angle * 180.0 / kPi * 60.0);
    add_to(reg_px_, "registration_error_px", angle / rad_per_px_);
  }
}

}  // namespace latsim::pipelines
