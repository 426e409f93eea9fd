#include "latsim/pxpl5/view_workload.hpp"
#include "latsim/units/units.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace latsim::pxpl5 {

namespace {


/// A corner in eye space as (x, y, d): d = distance in front of the eye.
struct EyePoint {
  double x, y, d;
};

EyePoint to_eye(const glm::dvec3& p, const tracker::Pose& pose, const glm::dquat& inverse) {
  const glm::dvec3 e = inverse * (p - pose.position_m);
  return {e.x, e.y, -e.z};
}

/// Whether all three corners lie outside one plane of the frustum (the four
/// side planes pass through the eye; the fifth is the near plane).
bool outside_one_plane(const std::array<EyePoint, 3>& c, double tan_h, double tan_v, double near_m) {
  const auto all = [&c](auto outside) { return outside(c[0]) && outside(c[1]) && outside(c[2]); };
  return all([&](const EyePoint& p) { return p.x < -p.d * tan_h; }) ||
         all([&](const EyePoint& p) { return p.x > p.d * tan_h; }) ||
         all([&](const EyePoint& p) { return p.y < -p.d * tan_v; }) ||
         all([&](const EyePoint& p) { return p.y > p.d * tan_v; }) ||
         all([&](const EyePoint& p) { return p.d < near_m; });
}

/// The polygon left of a triangle in front of the near plane (Sutherland-Hodgman, one plane).
int clip_near(const std::array<EyePoint, 3>& in, double near_m, std::array<EyePoint, 4>& out) {
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    const EyePoint& a = in[i];
    const EyePoint& b = in[(i + 1) % 3];
    const bool a_in = a.d >= near_m, b_in = b.d >= near_m;
    if (a_in) out[n++] = a;
    if (a_in != b_in) {
      const double s = (near_m - a.d) / (b.d - a.d);
      out[n++] = EyePoint{a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), near_m};
    }
  }
  return n;
}

/// The interval of screen slopes (x / d) a circle of radius r about (a, d)
/// covers, seen from the origin: the two tangents through it, or everything
/// when the circle reaches the near plane.
void slope_interval(double a, double d, double r, double near_m, double& lo, double& hi) {
  if (d - r < near_m) {
    lo = -INFINITY;
    hi = INFINITY;
    return;
  }
  const double root = r * std::sqrt(a * a + d * d - r * r), den = d * d - r * r;
  lo = (a * d - root) / den;
  hi = (a * d + root) / den;
}

}  // namespace

ViewBinner::ViewBinner(std::vector<WorldTriangle> triangles, ViewScreen screen, std::vector<WorldSphere> spheres)
    : triangles_(std::move(triangles)), spheres_(std::move(spheres)), screen_(screen) {
  if (!(screen_.hfov_deg > 0.0 && screen_.hfov_deg < 180.0) || screen_.width_px < 1 || screen_.height_px < 1 ||
      screen_.region_px < 1 || !(screen_.near_m > 0.0))
    throw std::invalid_argument("ViewBinner: bad screen");
  tan_half_h_ = std::tan(units::deg_to_rad(0.5 * screen_.hfov_deg));
  // Square pixels: the vertical extent follows from the aspect ratio.
  tan_half_v_ = tan_half_h_ * screen_.height_px / screen_.width_px;
}

void ViewBinner::regions_of(const WorldTriangle& triangle, const tracker::Pose& pose, std::vector<int>& out) const {
  out.clear();
  const glm::dquat inverse = glm::conjugate(pose.orientation);
  const std::array<EyePoint, 3> c{to_eye(triangle[0], pose, inverse), to_eye(triangle[1], pose, inverse),
                                  to_eye(triangle[2], pose, inverse)};
  if (outside_one_plane(c, tan_half_h_, tan_half_v_, screen_.near_m)) return;
  if (screen_.cull_back_faces) {
    // Counter-clockwise corners face their normal; the eye sits at the origin of eye space.
    const glm::dvec3 a(c[0].x, c[0].y, -c[0].d), b(c[1].x, c[1].y, -c[1].d), e(c[2].x, c[2].y, -c[2].d);
    if (glm::dot(glm::cross(b - a, e - a), -a) <= 0.0) return;
  }
  std::array<EyePoint, 4> poly{};
  const int n = clip_near(c, screen_.near_m, poly);
  const double w = screen_.width_px, h = screen_.height_px;
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (int i = 0; i < n; ++i) {
    // Pixel coordinates: x from the left edge, y from the top edge.
    const double x = (poly[i].x / poly[i].d / tan_half_h_ + 1.0) * 0.5 * w;
    const double y = (1.0 - poly[i].y / poly[i].d / tan_half_v_) * 0.5 * h;
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  }
  if (n == 0) return;
  box_regions(x0, x1, y0, y1, out);
}

void ViewBinner::regions_of(const WorldSphere& sphere, const tracker::Pose& pose, std::vector<int>& out) const {
  out.clear();
  const EyePoint c = to_eye(sphere.centre_m, pose, glm::conjugate(pose.orientation));
  const double r = sphere.radius_m;
  // Wholly beyond the near plane or one side plane (distances along the planes' unit normals).
  const double nh = std::sqrt(1.0 + tan_half_h_ * tan_half_h_), nv = std::sqrt(1.0 + tan_half_v_ * tan_half_v_);
  if (c.d + r < screen_.near_m || (c.x + c.d * tan_half_h_) / nh < -r || (c.d * tan_half_h_ - c.x) / nh < -r ||
      (c.y + c.d * tan_half_v_) / nv < -r || (c.d * tan_half_v_ - c.y) / nv < -r)
    return;
  double u0, u1, v0, v1;
  slope_interval(c.x, c.d, r, screen_.near_m, u0, u1);
  slope_interval(c.y, c.d, r, screen_.near_m, v0, v1);
  const double w = screen_.width_px, h = screen_.height_px;
  box_regions((u0 / tan_half_h_ + 1.0) * 0.5 * w, (u1 / tan_half_h_ + 1.0) * 0.5 * w,
              (1.0 - v1 / tan_half_v_) * 0.5 * h, (1.0 - v0 / tan_half_v_) * 0.5 * h, out);
}

void ViewBinner::box_regions(double x0, double x1, double y0, double y1, std::vector<int>& out) const {
  const double w = screen_.width_px, h = screen_.height_px;
  x0 = std::max(x0, 0.0);
  y0 = std::max(y0, 0.0);
  x1 = std::min(x1, w);
  y1 = std::min(y1, h);
  if (x0 >= w || y0 >= h || x1 <= 0.0 || y1 <= 0.0 || x0 > x1 || y0 > y1) return;
  const double r = screen_.region_px;
  const int cols = screen_.columns(), rows = screen_.rows();
  const int c0 = std::clamp(static_cast<int>(std::floor(x0 / r)), 0, cols - 1);
  const int c1 = std::clamp(static_cast<int>(std::ceil(x1 / r)) - 1, c0, cols - 1);
  const int r0 = std::clamp(static_cast<int>(std::floor(y0 / r)), 0, rows - 1);
  const int r1 = std::clamp(static_cast<int>(std::ceil(y1 / r)) - 1, r0, rows - 1);
  for (int row = r0; row <= r1; ++row)
    for (int col = c0; col <= c1; ++col) out.push_back(row * cols + col);
}

EyeWork ViewBinner::bin(const tracker::Pose& pose, int processors) const {
  EyeWork w;
  w.bins = BinCounts(processors, screen_.regions());
  w.on_screen.assign(triangles_.size(), 0);
  std::vector<int> covered;
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    regions_of(triangles_[t], pose, covered);
    const bool visible = !covered.empty();
    w.on_screen[t] = visible ? 1 : 0;
    w.on_screen_count += visible ? 1 : 0;
    w.bins.add_triangle(static_cast<int64_t>(t), visible, covered);
  }
  for (std::size_t k = 0; k < spheres_.size(); ++k) {
    regions_of(spheres_[k], pose, covered);
    w.spheres_on_screen_count += covered.empty() ? 0 : 1;
    w.bins.add_sphere(static_cast<int64_t>(triangles_.size() + k), !covered.empty(), covered);
  }
  return w;
}

ViewWorkload::ViewWorkload(ViewBinner binner, std::function<tracker::Pose(int64_t, int)> pose_of)
    : binner_(std::move(binner)), pose_of_(std::move(pose_of)) {}

const EyeWork& ViewWorkload::work(int64_t sample_token, int eye, int processors) {
  const auto key = std::make_tuple(sample_token, eye, processors);
  auto it = recent_.find(key);
  if (it != recent_.end()) return it->second;
  // Tokens grow with time: dropping the smallest keys keeps the recent ones.
  while (recent_.size() >= 8) recent_.erase(recent_.begin());
  return recent_.emplace(key, binner_.bin(pose_of_(sample_token, eye), processors)).first->second;
}

}  // namespace latsim::pxpl5
