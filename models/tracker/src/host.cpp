#include "latsim/tracker/host.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace latsim::tracker {

glm::dmat4 view_matrix(const Pose& pose) {
  // Eye-to-world is T(p) R(q); its inverse is R(q)^T T(-p), and the
  // conjugate of a unit quaternion is the transposed rotation.
  return glm::mat4_cast(glm::conjugate(pose.orientation)) * glm::translate(glm::dmat4(1.0), -pose.position_m);
}

HostFrame compute_views(const TrackerSample& sample, double ipd_m, bool stereo) {
  HostFrame frame;
  frame.sample = sample;
  frame.stereo = stereo;
  const Pose& head = sample.pose;
  Pose left = head;
  Pose right = head;
  if (stereo) {
    const glm::dvec3 half_offset = head.orientation * glm::dvec3{0.5 * ipd_m, 0.0, 0.0};
    left.position_m = head.position_m - half_offset;
    right.position_m = head.position_m + half_offset;
  }
  frame.left = EyeView{left, view_matrix(left)};
  frame.right = EyeView{right, view_matrix(right)};
  return frame;
}

}  // namespace latsim::tracker
