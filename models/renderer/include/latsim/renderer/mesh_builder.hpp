// Small geometry helpers that append tessellated quads and boxes to a Scene.
#pragma once

#include "latsim/renderer/scene.hpp"

#include <glm/vec3.hpp>

#include <functional>

namespace latsim::renderer {

/// Colour of one tile of a tessellated face, given the tile's column u and row v.
using TileColour = std::function<glm::vec3(int tile_u, int tile_v)>;

/// Appends the parallelogram origin + a*edge_u + b*edge_v (a, b in [0, 1]) to the current
/// object, cut into tiles no longer than tile_m along each edge (tile_m <= 0: one tile).
/// Tiles share exactly the same corner coordinates, so the surface stays watertight and
/// a tile size dividing the region size puts tile edges on region boundaries.
void add_tiled_quad(Scene& scene, const glm::dvec3& origin_m, const glm::dvec3& edge_u_m,
                    const glm::dvec3& edge_v_m, double tile_m, const TileColour& colour);

/// Appends the six faces of an axis-aligned box to the current object, each tiled as above.
void add_tiled_box(Scene& scene, const glm::dvec3& min_m, const glm::dvec3& max_m, double tile_m,
                   const TileColour& colour);

/// Appends an untiled axis-aligned box of one colour (12 triangles).
void add_box(Scene& scene, const glm::dvec3& min_m, const glm::dvec3& max_m,
             const glm::vec3& colour);

/// Appends a sphere as a subdivided octahedron pushed out onto it: 8 x
/// divisions^2 triangles (divisions >= 1) in the sphere's colour.
void add_sphere_mesh(Scene& scene, const Sphere& sphere, int divisions);

/// The scene with its spheres drawn as triangles (add_sphere_mesh, 72 each),
/// all in one object "spheres" after the others; a scene without spheres unchanged.
Scene tessellate_spheres(const Scene& scene);

/// A saturated colour that differs clearly between consecutive indices (golden-angle hues).
glm::vec3 distinct_colour(int index);

}  // namespace latsim::renderer
