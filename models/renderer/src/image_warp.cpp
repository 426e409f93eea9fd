#include "latsim/renderer/image_warp.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace latsim::renderer {

bool inside_rotated_source(const Camera& camera, const glm::dquat& source, const glm::dquat& shown, int x, int y) {
  const glm::dvec3 world = camera.pixel_ray(x, y, shown);
  const glm::dvec3 d = glm::conjugate(glm::normalize(source)) * world;
  if (!(d.z < 0.0)) return false;
  const double px = 0.5 * camera.width_px() + camera.focal_px() * d.x / -d.z;
  const double py = 0.5 * camera.height_px() - camera.focal_px() * d.y / -d.z;
  return px >= 0.0 && px < camera.width_px() && py >= 0.0 && py < camera.height_px();
}

namespace {

/// One source pixel centre as seen from the destination pose.
struct Projected {
  glm::dvec2 p{0.0};                                   ///< continuous destination pixel coordinates
  double depth = std::numeric_limits<double>::infinity();  ///< along the destination view axis; inf = sky
  bool valid = false;                                  ///< in front of the destination eye
};

class Warper {
 public:
  Warper(const Frame& source, const Camera& camera, const tracker::Pose& from, const tracker::Pose& to, const glm::vec3& undefined,
         double break_ratio)
      : src_(source), cam_(camera), w_(camera.width_px()), h_(camera.height_px()), break_ratio_(break_ratio) {
    if (source.colour.width != w_ || source.colour.height != h_ || source.depth.width != w_ || source.depth.height != h_)
      throw std::invalid_argument("warp_with_depth: the source frame must match the camera's size");
    out_.frame = Frame::cleared(w_, h_, undefined);
    out_.defined.assign(static_cast<size_t>(w_) * static_cast<size_t>(h_), 0);
    zbuf_.assign(out_.defined.size(), std::numeric_limits<double>::infinity());
    project_all(from, to);
  }

  WarpedFrame run() {
    for (int y = 0; y + 1 < h_; ++y)
      for (int x = 0; x + 1 < w_; ++x) draw_quad(x, y);
    // A pixel no continuous quad touches (a lone sky pixel between surfaces)
    // still lands where its own centre goes, if nothing nearer is there.
    for (int y = 0; y < h_; ++y)
      for (int x = 0; x < w_; ++x) draw_point(x, y);
    out_.undefined_px = static_cast<int64_t>(std::count(out_.defined.begin(), out_.defined.end(), uint8_t{0}));
    return std::move(out_);
  }

 private:
  size_t idx(int x, int y) const { return static_cast<size_t>(y) * static_cast<size_t>(w_) + static_cast<size_t>(x); }

  void project_all(const tracker::Pose& from, const tracker::Pose& to) {
    grid_.resize(static_cast<size_t>(w_) * static_cast<size_t>(h_));
    const glm::dquat to_head = glm::conjugate(glm::normalize(to.orientation));
    for (int y = 0; y < h_; ++y)
      for (int x = 0; x < w_; ++x) {
        const glm::dvec3 dir = cam_.pixel_ray(x, y, from.orientation);
        const double dist = src_.depth.at(x, y);
        Projected& g = grid_[idx(x, y)];
        // A point at infinity moves with the rotation only.
        const bool sky = !std::isfinite(dist);
        const glm::dvec3 d = sky ? to_head * dir : to_head * (from.position_m + dir * dist - to.position_m);
        if (!(d.z < 0.0)) continue;
        g.valid = true;
        g.depth = sky ? std::numeric_limits<double>::infinity() : -d.z;
        g.p = glm::dvec2(0.5 * w_ + cam_.focal_px() * d.x / -d.z, 0.5 * h_ - cam_.focal_px() * d.y / -d.z);
      }
  }

  bool continuous(const std::array<const Projected*, 4>& c) const {
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    int sky = 0;
    for (const Projected* q : c) {
      if (!q->valid) return false;
      if (!std::isfinite(q->depth)) {
        ++sky;
        continue;
      }
      lo = std::min(lo, q->depth);
      hi = std::max(hi, q->depth);
    }
    if (sky == 4) return true;
    return sky == 0 && hi <= lo * break_ratio_;
  }

  void draw_quad(int x, int y) {
    const std::array<int, 4> xs{x, x + 1, x, x + 1}, ys{y, y, y + 1, y + 1};
    std::array<const Projected*, 4> c{};
    for (int i = 0; i < 4; ++i) c[static_cast<size_t>(i)] = &grid_[idx(xs[static_cast<size_t>(i)], ys[static_cast<size_t>(i)])];
    if (!continuous(c)) return;
    // Two triangles: (00, 10, 11) and (00, 11, 01).
    draw_triangle(c, xs, ys, {0, 1, 3});
    draw_triangle(c, xs, ys, {0, 3, 2});
  }

  void draw_point(int x, int y) {
    const Projected& g = grid_[idx(x, y)];
    if (!g.valid) return;
    const int px = static_cast<int>(std::floor(g.p.x)), py = static_cast<int>(std::floor(g.p.y));
    if (px < 0 || px >= w_ || py < 0 || py >= h_) return;
    const size_t o = idx(px, py);
    if (out_.defined[o]) return;
    zbuf_[o] = g.depth;
    out_.frame.colour.at(px, py) = src_.colour.at(x, y);
    out_.frame.depth.at(px, py) = src_.depth.at(x, y);
    out_.defined[o] = 1;
  }

  void draw_triangle(const std::array<const Projected*, 4>& c, const std::array<int, 4>& xs,
                     const std::array<int, 4>& ys, std::array<int, 3> v) {
    const glm::dvec2 a = c[static_cast<size_t>(v[0])]->p, b = c[static_cast<size_t>(v[1])]->p,
                     e = c[static_cast<size_t>(v[2])]->p;
    const double area = (b.x - a.x) * (e.y - a.y) - (b.y - a.y) * (e.x - a.x);
    if (std::abs(area) < 1e-12) return;
    // Pixel centres sit at +0.5; the slack keeps a centre that lies on a
    // vertex up to rounding inside the box.
    constexpr double kBox = 1e-6;
    const int x0 = std::max(0, static_cast<int>(std::ceil(std::min({a.x, b.x, e.x}) - 0.5 - kBox)));
    const int x1 = std::min(w_ - 1, static_cast<int>(std::floor(std::max({a.x, b.x, e.x}) - 0.5 + kBox)));
    const int y0 = std::max(0, static_cast<int>(std::ceil(std::min({a.y, b.y, e.y}) - 0.5 - kBox)));
    const int y1 = std::min(h_ - 1, static_cast<int>(std::floor(std::max({a.y, b.y, e.y}) - 0.5 + kBox)));
    // Inclusive edges with slack for the float depths: a pixel centre on a
    // shared edge or corner (every one of them, for an identity warp) must
    // not fall between the quads.
    constexpr double kEps = 1e-4;
    for (int py = y0; py <= y1; ++py)
      for (int px = x0; px <= x1; ++px) {
        const glm::dvec2 q(px + 0.5, py + 0.5);
        const double l0 = ((b.x - q.x) * (e.y - q.y) - (b.y - q.y) * (e.x - q.x)) / area;
        const double l1 = ((e.x - q.x) * (a.y - q.y) - (e.y - q.y) * (a.x - q.x)) / area;
        const double l2 = 1.0 - l0 - l1;
        if (l0 < -kEps || l1 < -kEps || l2 < -kEps) continue;
        const std::array<double, 3> l{l0, l1, l2};
        write(px, py, l, c, xs, ys, v);
      }
  }

  void write(int px, int py, const std::array<double, 3>& l, const std::array<const Projected*, 4>& c,
             const std::array<int, 4>& xs, const std::array<int, 4>& ys, const std::array<int, 3>& v) {
    double depth = 0.0;
    bool sky = false;
    for (int i = 0; i < 3; ++i) {
      const double d = c[static_cast<size_t>(v[static_cast<size_t>(i)])]->depth;
      if (!std::isfinite(d)) sky = true;
      else depth += l[static_cast<size_t>(i)] * d;
    }
    if (sky) depth = std::numeric_limits<double>::infinity();
    const size_t o = idx(px, py);
    if (out_.defined[o] && !(depth < zbuf_[o])) return;
    zbuf_[o] = depth;
    const size_t nearest = static_cast<size_t>(
        v[static_cast<size_t>(std::max_element(l.begin(), l.end()) - l.begin())]);
    const int sx = xs[nearest], sy = ys[nearest];
    out_.frame.colour.at(px, py) = src_.colour.at(sx, sy);
    // Stored as the distance along the pixel's ray, as the ray caster does.
    out_.frame.depth.at(px, py) =
        sky ? std::numeric_limits<float>::infinity()
            : static_cast<float>(depth / -cam_.head_direction(px + 0.5, py + 0.5).z);
    out_.defined[o] = 1;
  }

  const Frame& src_;
  const Camera& cam_;
  int w_, h_;
  double break_ratio_;
  std::vector<Projected> grid_;
  std::vector<double> zbuf_;  ///< destination view-axis depth of what each pixel shows
  WarpedFrame out_;
};

}  // namespace

WarpedFrame warp_with_depth(const Frame& source, const Camera& camera, const tracker::Pose& source_pose,
                            const tracker::Pose& shown_pose, const glm::vec3& undefined, double break_ratio) {
  if (!(break_ratio >= 1.0)) throw std::invalid_argument("warp_with_depth: break_ratio must be at least 1");
  return Warper(source, camera, source_pose, shown_pose, undefined, break_ratio).run();
}

}  // namespace latsim::renderer
