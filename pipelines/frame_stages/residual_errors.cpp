#include "frame_stages/residual_errors.hpp"

#include <algorithm>

#include <glm/geometric.hpp>

namespace latsim::pipelines::frame_stages {

namespace {
constexpr double kDegPerRad = 57.295779513082320876798;
}  // namespace

ResidualErrors::ResidualErrors(const Compositor& compositor, results::LatencyRecorder& recorder,
                               const tracker::MotionSource& motion, double ipd_m, bool stereo)
    : compositor_(compositor), recorder_(recorder), motion_(motion), ipd_m_(ipd_m), stereo_(stereo) {}

void ResidualErrors::on_scanout(const display::ScanoutSpan& span) {
  const int rewarps = compositor_.rewarps_of(span.image_id);
  if (rewarps < 0) return;
  const results::ImageRecord* img = recorder_.images().find(span.image_id);
  if (img == nullptr) return;
  if (!orientation_) {
    orientation_ = &recorder_.distribution_ref("residual_orientation_error_deg");
    position_ = &recorder_.distribution_ref("residual_position_error_mm");
  }
  // One value per line, each against the truth at the photon time of the
  // line's first pixel: a span of several lines (field fidelity) has one
  // sample per line; a span within one line (pixel fidelity: the pixels of a
  // line, cut where the image changes) counts only when it starts the line,
  // and then as the line does at line fidelity. Along one line the truth
  // moves for a line period (about 9 us at 90 Hz: 0.001 deg at 120 deg/s),
  // so judging every pixel would cost as much as the rest of the run
  // together and change nothing a user reads; the figures are the same at
  // line and pixel fidelity.
  const bool within_line = span.line_end - span.line == 1;
  if (within_line && span.x_begin != 0) return;
  const uint64_t samples = within_line ? 1 : span.photons.count;
  Bucket& b = buckets_[static_cast<size_t>(std::min(rewarps, kBuckets - 1))];
  stats::TickStepper t(span.photons);
  for (uint64_t i = 0; i < samples; ++i, t.step()) {
    const tracker::Pose truth = tracker::eye_pose(motion_.pose_at(t.time()), span.eye, ipd_m_, stereo_);
    const double deg = tracker::angle_between(img->eye_pose.orientation, truth.orientation) * kDegPerRad;
    const double mm = glm::length(img->eye_pose.position_m - truth.position_m) * 1e3;
    orientation_->add(deg);
    position_->add(mm);
    b.orientation_deg.add(deg);
    b.position_mm.add(mm);
  }
}

}  // namespace latsim::pipelines::frame_stages
