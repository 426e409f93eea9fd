#include "latsim/arp/segmentation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>

#include <glm/geometric.hpp>

namespace latsim::arp {
namespace {

using renderer::Aabb;
using renderer::RegionGrid;
using renderer::RegionIndex;
using renderer::Scene;
using renderer::Triangle;

// A polygon corner during clipping, in double precision.
struct Corner {
  glm::dvec3 p;
  glm::dvec3 c;
};

// Which side of an axis-aligned plane is kept.
struct HalfSpace {
  int axis;      // 0 = x, 2 = z
  double value;  // plane coordinate
  bool keep_above;
};

bool inside(const Corner& v, const HalfSpace& h) {
  return h.keep_above ? v.p[h.axis] >= h.value : v.p[h.axis] <= h.value;
}

bool lexicographic_less(const glm::dvec3& a, const glm::dvec3& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

// The edge's crossing of the plane, from the endpoints in a fixed order so
// the regions on both sides compute the same bits.
Corner crossing(Corner a, Corner b, const HalfSpace& h) {
  if (lexicographic_less(b.p, a.p)) std::swap(a, b);
  const double t = (h.value - a.p[h.axis]) / (b.p[h.axis] - a.p[h.axis]);
  Corner r{a.p + t * (b.p - a.p), a.c + t * (b.c - a.c)};
  r.p[h.axis] = h.value;
  return r;
}

std::vector<Corner> clip(const std::vector<Corner>& poly, const HalfSpace& h) {
  std::vector<Corner> out;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Corner& a = poly[i];
    const Corner& b = poly[(i + 1) % poly.size()];
    const bool a_in = inside(a, h);
    const bool b_in = inside(b, h);
    if (a_in) out.push_back(a);
    if (a_in != b_in) out.push_back(crossing(a, b, h));
  }
  return out;
}

double twice_area(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  return std::sqrt(glm::dot(n, n));
}

Aabb triangle_bounds(const Triangle& t) {
  Aabb box;
  for (const auto& p : t.position_m) box.extend(glm::dvec3(p));
  return box;
}

// Appends the parts of `tri` inside region `r` to `out` (outer grid sides are not clipped).
void clip_to_region(const Triangle& tri, RegionIndex r, const RegionGrid& grid, std::vector<Triangle>& out) {
  std::vector<Corner> poly;
  for (int i = 0; i < 3; ++i) poly.push_back({glm::dvec3(tri.position_m[i]), glm::dvec3(tri.colour[i])});
  const Aabb cell = grid.region_bounds(r);
  std::vector<HalfSpace> planes;
  if (r.ix > 0) planes.push_back({0, cell.min_m.x, true});
  if (r.ix < grid.count_x() - 1) planes.push_back({0, cell.max_m.x, false});
  if (r.iz > 0) planes.push_back({2, cell.min_m.z, true});
  if (r.iz < grid.count_z() - 1) planes.push_back({2, cell.max_m.z, false});
  for (const HalfSpace& h : planes) {
    poly = clip(poly, h);
    if (poly.size() < 3) return;
  }
  for (size_t i = 1; i + 1 < poly.size(); ++i) {
    if (twice_area(poly[0].p, poly[i].p, poly[i + 1].p) <= 0.0) continue;
    Triangle t;
    for (int k = 0; k < 3; ++k) {
      const Corner& v = k == 0 ? poly[0] : poly[i + static_cast<size_t>(k) - 1];
      t.position_m[static_cast<size_t>(k)] = glm::vec3(v.p);
      t.colour[static_cast<size_t>(k)] = glm::vec3(v.c);
    }
    out.push_back(t);
  }
}

// Vertices are matched on a 10 micrometre lattice: far below any tear worth
// measuring, far above float rounding of coordinates of a few tens of metres.
std::array<int64_t, 3> vertex_key(const glm::vec3& p) {
  constexpr double kLattice_per_m = 1e5;
  return {std::llround(p.x * kLattice_per_m), std::llround(p.y * kLattice_per_m), std::llround(p.z * kLattice_per_m)};
}

void find_shared_vertices(SegmentedScene& out) {
  std::map<std::array<int64_t, 3>, std::pair<glm::dvec3, std::set<uint32_t>>> users;
  for (uint32_t s = 0; s < out.segments.size(); ++s) {
    const auto& obj = out.scene.objects()[out.segments[s].scene_object];
    for (uint32_t t = obj.first_triangle; t < obj.first_triangle + obj.triangle_count; ++t) {
      for (const auto& p : out.scene.triangles()[t].position_m) {
        auto& entry = users[vertex_key(p)];
        entry.first = glm::dvec3(p);
        entry.second.insert(s);
      }
    }
  }
  for (const auto& [key, entry] : users) {
    const std::vector<uint32_t> segs(entry.second.begin(), entry.second.end());
    for (size_t i = 0; i < segs.size(); ++i) {
      for (size_t j = i + 1; j < segs.size(); ++j) {
        // Segments covering the same regions always share a memory: no tear possible.
        if (out.segments[segs[i]].regions == out.segments[segs[j]].regions) continue;
        out.shared_vertices.push_back({entry.first, segs[i], segs[j]});
      }
    }
  }
}

std::vector<int> linear_regions(const RegionGrid& grid, const Aabb& box) {
  std::vector<int> ids;
  for (RegionIndex r : grid.regions_of(box)) ids.push_back(grid.linear_index(r));
  return ids;
}

// The triangles of an object inside each region it reaches into (clipped at boundaries).
std::map<int, std::vector<Triangle>> cut_object(const Scene& scene, uint32_t id, const RegionGrid& grid) {
  const auto& obj = scene.objects()[id];
  std::map<int, std::vector<Triangle>> pieces;
  for (uint32_t t = obj.first_triangle; t < obj.first_triangle + obj.triangle_count; ++t) {
    const Triangle& tri = scene.triangles()[t];
    const auto regions = grid.regions_of(triangle_bounds(tri));
    if (regions.size() == 1) {
      pieces[grid.linear_index(regions[0])].push_back(tri);
      continue;
    }
    for (RegionIndex r : regions) clip_to_region(tri, r, grid, pieces[grid.linear_index(r)]);
  }
  std::erase_if(pieces, [](const auto& piece) { return piece.second.empty(); });
  return pieces;
}

bool stays_whole(const Scene& scene, uint32_t id, const RegionGrid& grid) {
  const auto& obj = scene.objects()[id];
  return obj.animated || grid.regions_of(obj.bounds).size() <= 1;
}

void copy_object(const Scene& in, uint32_t id, const RegionGrid& grid, SegmentedScene& out) {
  const auto& obj = in.objects()[id];
  Segment seg;
  seg.source_object = id;
  seg.scene_object = out.scene.begin_object(obj.name, obj.animated);
  seg.regions = linear_regions(grid, obj.bounds);
  seg.animated = obj.animated;
  for (uint32_t t = obj.first_triangle; t < obj.first_triangle + obj.triangle_count; ++t) {
    out.scene.add_triangle(in.triangles()[t]);
  }
  out.segments.push_back(seg);
}

}  // namespace

SegmentedScene segment_scene(const Scene& scene, const RegionGrid& grid) {
  SegmentedScene out;
  out.segmented = true;
  for (uint32_t id = 0; id < scene.object_count(); ++id) {
    const auto& obj = scene.objects()[id];
    if (stays_whole(scene, id, grid)) {
      copy_object(scene, id, grid, out);
      continue;
    }
    for (const auto& [region, triangles] : cut_object(scene, id, grid)) {
      const RegionIndex r = grid.from_linear(region);
      Segment seg;
      seg.source_object = id;
      seg.scene_object = out.scene.begin_object(obj.name + "@" + std::to_string(r.ix) + "_" + std::to_string(r.iz));
      seg.regions = {region};
      for (const Triangle& t : triangles) out.scene.add_triangle(t);
      out.segments.push_back(seg);
    }
  }
  find_shared_vertices(out);
  return out;
}

SegmentedScene whole_objects(const Scene& scene, const RegionGrid& grid) {
  SegmentedScene out;
  for (uint32_t id = 0; id < scene.object_count(); ++id) {
    copy_object(scene, id, grid, out);
    if (!stays_whole(scene, id, grid))
      out.segments.back().object_segments = static_cast<int64_t>(cut_object(scene, id, grid).size());
  }
  find_shared_vertices(out);
  return out;
}

}  // namespace latsim::arp
