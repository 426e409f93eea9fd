// The orientation a run showed at one point of the screen, refresh by refresh.
#pragma once

#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "latsim/des/time.hpp"

namespace latsim::measurement {

/// A point of the screen: x as a fraction of the width, y as a fraction of a
/// field's active lines (0, 0: top left).
struct ScreenPoint {
  double x = 0.5;
  double y = 0.5;
};

/// One lighting of the point: the middle of its lit interval, the interval's
/// length (0: an impulse) and the head orientation the image there was drawn
/// (or warped, or looked up) with.
struct ShownSample {
  des::Time photon;
  des::Time lit;
  glm::dquat orientation{1.0, 0.0, 0.0, 0.0};
  /// A tracked controller drawn in the image: the orientation a viewer sees it
  /// at (see controller_seen) and when the pose drawn was measured.
  bool controller_drawn = false;
  glm::dquat controller{1.0, 0.0, 0.0, 0.0};
  des::Time controller_measured;
  /// When the pixel was written: its transition from the previous value
  /// starts there (a camera sees it through the panel's rise, PanelRise).
  des::Time written;
};

/// The world orientation at which a viewer whose head is truly at
/// `true_head` sees a controller drawn at `drawn` in an image shown with
/// head orientation `shown_head`: the image puts it at shown_head⁻¹·drawn in
/// the view, which the viewer's head carries to true_head·shown_head⁻¹·drawn.
/// A head error moves the controller with the rest of the world.
glm::dquat controller_seen(const glm::dquat& true_head, const glm::dquat& shown_head, const glm::dquat& drawn);

/// The shown orientation at one pixel of eye 0, one sample per refresh: what
/// apparent latency and the camera rig compare with the true motion.
class ShownTrace {
 public:
  /// The pixel of `point` on a screen `width_px` wide with `lines` active lines per field.
  ShownTrace(ScreenPoint point, int width_px, int lines);
  int line() const { return line_; }
  int column() const { return column_; }
  void add(const ShownSample& sample) { samples_.push_back(sample); }
  /// The samples in photon order (spans reach the recorder almost in order;
  /// address recalculation lines that waited for their sample come later).
  const std::vector<ShownSample>& sorted();

 private:
  int line_;
  int column_;
  std::vector<ShownSample> samples_;
};

/// Signed angle in degrees, in (−180, 180], of the rotation from `from` to
/// `to` about `axis` (unit length): the twist of to·from⁻¹ about the axis.
double twist_deg(const glm::dquat& from, const glm::dquat& to, const glm::dvec3& axis);

}  // namespace latsim::measurement
