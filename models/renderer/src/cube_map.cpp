#include "latsim/renderer/cube_map.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace latsim::renderer {

CubeMap::CubeMap(const glm::dvec3& centre_m, int face_px, const glm::vec3& background)
    : centre_m_(centre_m), face_px_(face_px) {
  if (face_px < 1) throw std::invalid_argument("cube map: face_px must be >= 1, got " + std::to_string(face_px));
  texels_.assign(static_cast<size_t>(kFaceCount) * static_cast<size_t>(face_px) * static_cast<size_t>(face_px),
                 CubeTexel{background, std::numeric_limits<float>::infinity()});
}

size_t CubeMap::index(int face, int i, int j) const {
  if (face < 0 || face >= kFaceCount || i < 0 || j < 0 || i >= face_px_ || j >= face_px_) {
    throw std::out_of_range("cube map: texel (" + std::to_string(face) + ", " + std::to_string(i) + ", " +
                            std::to_string(j) + ") is outside a cube of " + std::to_string(face_px_) +
                            " texels per side");
  }
  const size_t n = static_cast<size_t>(face_px_);
  return (static_cast<size_t>(face) * n + static_cast<size_t>(j)) * n + static_cast<size_t>(i);
}

CubeTexel& CubeMap::texel(int face, int i, int j) { return texels_[index(face, i, j)]; }
const CubeTexel& CubeMap::texel(int face, int i, int j) const { return texels_[index(face, i, j)]; }

glm::dvec3 CubeMap::texel_direction(int face, int i, int j) const {
  // (s, t) in [-1, 1] across the face; the table is the inverse of the OpenGL major-axis
  // selection used by lookup(), so lookup(texel_direction(f, i, j)) returns that texel.
  const double s = (i + 0.5) / face_px_ * 2.0 - 1.0;
  const double t = (j + 0.5) / face_px_ * 2.0 - 1.0;
  glm::dvec3 d;
  switch (face) {
    case 0: d = {1.0, -t, -s}; break;
    case 1: d = {-1.0, -t, s}; break;
    case 2: d = {s, 1.0, t}; break;
    case 3: d = {s, -1.0, -t}; break;
    case 4: d = {s, -t, 1.0}; break;
    case 5: d = {-s, -t, -1.0}; break;
    default:
      throw std::out_of_range("cube map: face " + std::to_string(face) + " is not in [0, 6)");
  }
  return glm::normalize(d);
}

CubeTexel CubeMap::lookup(const glm::dvec3& d) const {
  const double ax = std::fabs(d.x);
  const double ay = std::fabs(d.y);
  const double az = std::fabs(d.z);
  int face = 0;
  double sc = 0.0;
  double tc = 0.0;
  double ma = 0.0;
  // Ties between axes go to x, then y, then z: a fixed rule keeps lookups deterministic.
  if (ax >= ay && ax >= az) {
    face = d.x >= 0.0 ? 0 : 1;
    sc = d.x >= 0.0 ? -d.z : d.z;
    tc = -d.y;
    ma = ax;
  } else if (ay >= az) {
    face = d.y >= 0.0 ? 2 : 3;
    sc = d.x;
    tc = d.y >= 0.0 ? d.z : -d.z;
    ma = ay;
  } else {
    face = d.z >= 0.0 ? 4 : 5;
    sc = d.z >= 0.0 ? d.x : -d.x;
    tc = -d.y;
    ma = az;
  }
  if (!(ma > 0.0)) throw std::invalid_argument("cube map: lookup direction must not be zero");
  const auto texel_of = [this, ma](double c) {
    const int k = static_cast<int>(std::floor((c / ma + 1.0) * 0.5 * face_px_));
    return std::clamp(k, 0, face_px_ - 1);
  };
  return texels_[index(face, texel_of(sc), texel_of(tc))];
}

CubeMap render_cube(const RayCaster& caster, const glm::dvec3& eye_m, int face_px, const RenderOptions& options) {
  CubeMap cube(eye_m, face_px, options.background);
  std::vector<Ray> rays;
  rays.reserve(static_cast<size_t>(CubeMap::kFaceCount) * static_cast<size_t>(face_px) * static_cast<size_t>(face_px));
  for (int face = 0; face < CubeMap::kFaceCount; ++face) {
    for (int j = 0; j < face_px; ++j) {
      for (int i = 0; i < face_px; ++i) rays.push_back({eye_m, cube.texel_direction(face, i, j)});
    }
  }
  std::vector<Hit> hits(rays.size());
  caster.cast_rays(rays, hits, options);
  size_t k = 0;
  for (int face = 0; face < CubeMap::kFaceCount; ++face) {
    for (int j = 0; j < face_px; ++j) {
      for (int i = 0; i < face_px; ++i, ++k) cube.texel(face, i, j) = CubeTexel{hits[k].colour, hits[k].distance_m};
    }
  }
  return cube;
}

}  // namespace latsim::renderer
