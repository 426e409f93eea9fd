#include "latsim/arp/seam_meter.hpp"

#include <glm/geometric.hpp>

namespace latsim::arp {

SeamMeter::SeamMeter(const RegionPriorityModel& model, const renderer::RayCaster* occluder)
    : model_(model), occluder_(occluder) {}

bool SeamMeter::visible(const glm::dvec3& point_m, const glm::dvec3& eye_m) const {
  if (!occluder_) return true;
  const glm::dvec3 to = point_m - eye_m;
  const double distance = glm::length(to);
  if (!(distance > 0.0)) return true;
  const renderer::Hit hit = occluder_->cast(eye_m, to);
  // The point lies on a surface itself: a hit at its own distance (within float
  // rounding of the geometry, 5 mm plus 0.1 %) is the point, not an occluder.
  return !hit.hit || static_cast<double>(hit.distance_m) >= distance - (0.005 + 1e-3 * distance);
}

void SeamMeter::tear_gaps_px(const ShownRegions& shown, const glm::dquat& head, const glm::dvec3& eye_m,
                             const ScreenProjection& screen, std::vector<double>& gaps) const {
  for (const SharedVertex& v : model_.scene().shared_vertices) {
    const int ma = shown.memory_of_segment[v.segment_a];
    const int mb = shown.memory_of_segment[v.segment_b];
    if (ma == mb || ma < 0 || mb < 0) continue;
    const RegionView* va = shown.views[static_cast<size_t>(ma)];
    const RegionView* vb = shown.views[static_cast<size_t>(mb)];
    if (!va || !vb) continue;
    glm::dvec2 pa;
    glm::dvec2 pb;
    if (!screen.project(head, model_.drawn_direction(ma, v.position_m, *va), pa)) continue;
    if (!screen.project(head, model_.drawn_direction(mb, v.position_m, *vb), pb)) continue;
    if (!visible(v.position_m, eye_m)) continue;
    gaps.push_back(glm::length(pa - pb));
  }
}

std::vector<WarpedPoint> SeamMeter::warped_points(int memory, const std::vector<uint32_t>& segments,
                                                  const RegionView& view) const {
  std::vector<WarpedPoint> points;
  if (!model_.params().warping) return points;
  const SegmentedScene& scene = model_.scene();
  for (uint32_t s : segments) {
    const renderer::SceneObject& obj = scene.scene.objects()[scene.segments[s].scene_object];
    for (uint32_t t = obj.first_triangle; t < obj.first_triangle + obj.triangle_count; ++t) {
      WarpedPoint p;
      bool moved = false;
      for (const auto& corner : scene.scene.triangles()[t].position_m) {
        const glm::dvec3 c(corner);
        const glm::dvec3 offset = model_.warp_offset_m(memory, c, view);
        moved = moved || offset != glm::dvec3(0.0);
        p.true_m += c / 3.0;
        p.drawn_m += (c + offset) / 3.0;
      }
      if (moved) points.push_back(p);
    }
  }
  return points;
}

void SeamMeter::stretch_px(const std::vector<WarpedPoint>& points, const glm::dvec3& image_eye_m,
                           const glm::dquat& head, const glm::dvec3& eye_m, const ScreenProjection& screen,
                           std::vector<double>& stretch) const {
  for (const WarpedPoint& p : points) {
    glm::dvec2 drawn;
    glm::dvec2 truth;
    if (!screen.project(head, p.drawn_m - image_eye_m, drawn)) continue;
    if (!screen.project(head, p.true_m - eye_m, truth)) continue;
    if (!visible(p.true_m, eye_m)) continue;
    stretch.push_back(glm::length(drawn - truth));
  }
}

}  // namespace latsim::arp
