#include "latsim/pxpl5/view_workload.hpp"
#include "latsim/units/units.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

}  // namespace

ViewBinner::ViewBinner(std::vector<WorldTriangle> triangles, ViewScreen screen)
    : triangles_(std::move(triangles)), screen_(screen) {
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
  x0 = std::max(x0, 0.0);
  y0 = std::max(y0, 0.0);
  x1 = std::min(x1, w);
  y1 = std::min(y1, h);
  if (n == 0 || x0 >= w || y0 >= h || x1 <= 0.0 || y1 <= 0.0 || x0 > x1 || y0 > y1) return;
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
