// The view-dependent workload: the triangles inside each eye's view at the
// pose an image is computed with, binned into the regions they cover.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <tuple>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "latsim/pxpl5/workload.hpp"
#include "latsim/tracker/pose.hpp"

namespace latsim::pxpl5 {

/// A display-list triangle: three corners in world metres.
using WorldTriangle = std::array<glm::dvec3, 3>;

/// A display-list sphere: centre and radius in world metres.
struct WorldSphere {
  glm::dvec3 centre_m{0.0};
  double radius_m = 0.0;
};

/// The screen a view is binned onto: a pinhole with square pixels, tiled by
/// regions of region_px x region_px from the top left.
struct ViewScreen {
  double hfov_deg = 60.0;
  int width_px = 640;
  int height_px = 480;
  int region_px = 128;
  double near_m = 0.01;  ///< geometry nearer than this is clipped away
  /// Triangles facing away from the eye (corners clockwise as it sees them)
  /// are rejected like those outside the view (PHIGS PLUS face culling).
  bool cull_back_faces = false;

  int columns() const { return (width_px + region_px - 1) / region_px; }
  int rows() const { return (height_px + region_px - 1) / region_px; }
  int regions() const { return columns() * rows(); }
};

/// Finds, for one eye pose, the regions each triangle's screen-space bounding
/// box covers: a triangle all of whose corners lie beyond one plane of the
/// view frustum is outside the view; otherwise it is clipped against the near
/// plane, its corners projected, and the box of the projections, cut to the
/// screen, names the block of regions whose bins it goes into (none when the
/// box misses the screen). A box ending exactly on a region boundary does not
/// reach into the next region. Back faces are culled only when the screen
/// says so. A sphere is outside
/// when it lies wholly beyond one plane; its box is bounded by the planes
/// through the eye that touch it (the whole screen along an axis where it
/// reaches the near plane).
class ViewBinner {
 public:
  ViewBinner(std::vector<WorldTriangle> triangles, ViewScreen screen, std::vector<WorldSphere> spheres = {});

  int64_t triangles() const { return static_cast<int64_t>(triangles_.size()); }
  int64_t spheres() const { return static_cast<int64_t>(spheres_.size()); }
  const ViewScreen& screen() const { return screen_; }
  /// Regions (row * columns + column) that `triangle` covers seen from `pose`; empty when outside the view.
  void regions_of(const WorldTriangle& triangle, const tracker::Pose& pose, std::vector<int>& out) const;
  /// The same for a sphere.
  void regions_of(const WorldSphere& sphere, const tracker::Pose& pose, std::vector<int>& out) const;
  /// Every triangle, then every sphere, binned for `processors` display lists (dealt round-robin).
  EyeWork bin(const tracker::Pose& pose, int processors) const;

 private:
  /// The regions a screen box (pixels, x right and y down) overlaps once cut to the screen.
  void box_regions(double x0, double x1, double y0, double y1, std::vector<int>& out) const;

  std::vector<WorldTriangle> triangles_;
  std::vector<WorldSphere> spheres_;
  ViewScreen screen_;
  double tan_half_h_;
  double tan_half_v_;
};

/// The scene as each image sees it: the pose comes from the host sample the
/// image is computed with, so the load follows the head.
class ViewWorkload final : public WorkloadSource {
 public:
  /// `pose_of(token, eye)` is the eye pose of a host sample (-1: the starting view).
  ViewWorkload(ViewBinner binner, std::function<tracker::Pose(int64_t token, int eye)> pose_of);
  int64_t triangles() const override { return binner_.triangles(); }
  int64_t spheres() const override { return binner_.spheres(); }
  const EyeWork& work(int64_t sample_token, int eye, int processors) override;

 private:
  ViewBinner binner_;
  std::function<tracker::Pose(int64_t, int)> pose_of_;
  // RC asks for each eye once per frame and Slats for both eyes once per
  // field; a few recent results cover every repeat.
  std::map<std::tuple<int64_t, int, int>, EyeWork> recent_;
};

}  // namespace latsim::pxpl5
