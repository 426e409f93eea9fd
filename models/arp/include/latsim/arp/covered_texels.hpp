// How many texels of a cube display memory a triangle covers, seen from the
// memory's centre: the fill work a renderer does for it.
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include "latsim/renderer/scene.hpp"

namespace latsim::arp {

/// Solid angle in steradians subtended at `eye_m` by triangle (a, b, c):
/// Van Oosterom and Strackee's formula, tan(omega/2) = |a.(b x c)| /
/// (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|) with corners relative to the
/// eye, evaluated with atan2 so it stays exact for tiny and for huge triangles.
double solid_angle_sr(const glm::dvec3& eye_m, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

/// Texels per steradian of a cube map with `face_px` texels per face side in
/// direction d: a face at unit distance spans [-1, 1]^2, so a texel is
/// (2/face_px)^2 of area and subtends that divided by (1 + u^2 + v^2)^(3/2),
/// (u, v) the direction's face coordinates.
double cube_texels_per_sr(const glm::dvec3& direction, int face_px);

/// Texels of a face_px cube centred at `eye_m` whose area the triangle covers,
/// occluded or not (a depth-buffered renderer rasterises them all). The
/// triangle is split into four until each part subtends at most 0.05 sr (the
/// density then varies by a few percent across a part), and each part counts
/// its solid angle times the density at its centroid.
double triangle_texels(const glm::dvec3& eye_m, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                       int face_px);

/// The texels of every triangle of one scene object.
double object_texels(const renderer::Scene& scene, uint32_t object, const glm::dvec3& eye_m, int face_px);

}  // namespace latsim::arp
