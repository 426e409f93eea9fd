#include "latsim/renderer/mesh_builder.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace latsim::renderer {
namespace {

int tile_count(double length_m, double tile_m) {
  if (tile_m <= 0.0) return 1;
  // The small slack keeps a length that is an exact multiple of the tile from gaining a
  // sliver tile through rounding in the division.
  return std::max(1, static_cast<int>(std::ceil(length_m / tile_m - 1e-9)));
}

}  // namespace

void add_tiled_quad(Scene& scene, const glm::dvec3& origin_m, const glm::dvec3& edge_u_m,
                    const glm::dvec3& edge_v_m, double tile_m, const TileColour& colour) {
  const int count_u = tile_count(glm::length(edge_u_m), tile_m);
  const int count_v = tile_count(glm::length(edge_v_m), tile_m);
  // Every corner comes from the same expression of its integer grid position, so corners
  // shared by neighbouring tiles are bit-identical.
  auto corner = [&](int i, int j) {
    const double a = static_cast<double>(i) / count_u;
    const double b = static_cast<double>(j) / count_v;
    return glm::vec3(origin_m + a * edge_u_m + b * edge_v_m);
  };
  for (int j = 0; j < count_v; ++j) {
    for (int i = 0; i < count_u; ++i) {
      const glm::vec3 c = colour(i, j);
      const glm::vec3 p00 = corner(i, j);
      const glm::vec3 p10 = corner(i + 1, j);
      const glm::vec3 p11 = corner(i + 1, j + 1);
      const glm::vec3 p01 = corner(i, j + 1);
      scene.add_triangle(p00, p10, p11, c);
      scene.add_triangle(p00, p11, p01, c);
    }
  }
}

void add_tiled_box(Scene& scene, const glm::dvec3& min_m, const glm::dvec3& max_m, double tile_m,
                   const TileColour& colour) {
  const glm::dvec3 size = max_m - min_m;
  const glm::dvec3 ex(size.x, 0.0, 0.0);
  const glm::dvec3 ey(0.0, size.y, 0.0);
  const glm::dvec3 ez(0.0, 0.0, size.z);
  add_tiled_quad(scene, min_m, ex, ey, tile_m, colour);                     // -z face
  add_tiled_quad(scene, min_m + ez, ex, ey, tile_m, colour);                // +z face
  add_tiled_quad(scene, min_m, ez, ey, tile_m, colour);                     // -x face
  add_tiled_quad(scene, min_m + ex, ez, ey, tile_m, colour);                // +x face
  add_tiled_quad(scene, min_m, ex, ez, tile_m, colour);                     // -y face
  add_tiled_quad(scene, min_m + ey, ex, ez, tile_m, colour);                // +y face
}

void add_box(Scene& scene, const glm::dvec3& min_m, const glm::dvec3& max_m,
             const glm::vec3& colour) {
  add_tiled_box(scene, min_m, max_m, 0.0, [&](int, int) { return colour; });
}

void add_sphere_mesh(Scene& scene, const Sphere& sphere, int divisions) {
  const int n = std::max(1, divisions);
  const glm::dvec3 centre(sphere.centre_m);
  const double radius = sphere.radius_m;
  // A point of the face with corners a, b, c at grid step (i, j), on the sphere.
  const auto on_sphere = [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, int i, int j) {
    const glm::dvec3 p = a + (b - a) * (static_cast<double>(i) / n) + (c - a) * (static_cast<double>(j) / n);
    return glm::vec3(centre + glm::normalize(p) * radius);
  };
  for (int face = 0; face < 8; ++face) {
    const glm::dvec3 a((face & 1) ? -1.0 : 1.0, 0.0, 0.0);
    const glm::dvec3 b(0.0, (face & 2) ? -1.0 : 1.0, 0.0);
    const glm::dvec3 c(0.0, 0.0, (face & 4) ? -1.0 : 1.0);
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        scene.add_triangle(on_sphere(a, b, c, i, j), on_sphere(a, b, c, i + 1, j), on_sphere(a, b, c, i, j + 1),
                           sphere.colour);
        if (i + j + 2 <= n)
          scene.add_triangle(on_sphere(a, b, c, i + 1, j), on_sphere(a, b, c, i + 1, j + 1),
                             on_sphere(a, b, c, i, j + 1), sphere.colour);
      }
  }
}

Scene tessellate_spheres(const Scene& scene) {
  if (scene.spheres().empty()) return scene;
  Scene out;
  for (const SceneObject& object : scene.objects()) {
    out.begin_object(object.name, object.animated);
    for (uint32_t k = 0; k < object.triangle_count; ++k) out.add_triangle(scene.triangles()[object.first_triangle + k]);
  }
  out.begin_object("spheres");
  for (const Sphere& sphere : scene.spheres()) add_sphere_mesh(out, sphere, 3);
  return out;
}

glm::vec3 distinct_colour(int index) {
  // Golden-ratio steps around the hue circle never repeat and stay well apart.
  const double hue = std::fmod(0.1 + 0.6180339887498949 * index, 1.0) * 6.0;
  const int sector = static_cast<int>(hue);
  const float f = static_cast<float>(hue - sector);
  const float hi = 0.9f;
  const float lo = 0.15f;
  const float up = lo + (hi - lo) * f;
  const float down = hi - (hi - lo) * f;
  switch (sector % 6) {
    case 0: return {hi, up, lo};
    case 1: return {down, hi, lo};
    case 2: return {lo, hi, up};
    case 3: return {lo, down, hi};
    case 4: return {up, lo, hi};
    default: return {hi, lo, down};
  }
}

}  // namespace latsim::renderer
