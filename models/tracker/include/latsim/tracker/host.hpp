// The host application's step from a tracker sample to viewing transforms.
#pragma once

#include <glm/mat4x4.hpp>

#include "latsim/tracker/pose.hpp"
#include "latsim/tracker/tracker.hpp"

namespace latsim::tracker {

/// One eye's pose and its world-to-eye (view) matrix, OpenGL convention.
struct EyeView {
  Pose pose;
  glm::dmat4 view{1.0};
};

/// The viewing transforms the host sends down the pipeline for one sample.
struct HostFrame {
  TrackerSample sample;
  EyeView left;
  EyeView right;
  bool stereo = false;
};

/// The view matrix of a pose: the inverse of its eye-to-world transform.
glm::dmat4 view_matrix(const Pose& pose);

/// Viewing transforms for a sample. Stereo: each eye sits ipd_m / 2 from the
/// head origin along the head's x axis (left at -x, right at +x), looking the
/// same way as the head. Mono: both views are the head pose.
HostFrame compute_views(const TrackerSample& sample, double ipd_m, bool stereo);

}  // namespace latsim::tracker
