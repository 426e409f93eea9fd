// Six-face cube environment (colour + depth) rendered around a point, as held by an
// address-recalculation display memory.
#pragma once

#include "latsim/renderer/image.hpp"
#include "latsim/renderer/ray_caster.hpp"

#include <glm/vec3.hpp>

#include <vector>

namespace latsim::renderer {

/// What one cube texel holds.
struct CubeTexel {
  glm::vec3 colour{0.0f};
  /// Distance from the cube centre in metres; +infinity where nothing was hit.
  float depth_m = 0.0f;
};

/// Six square faces in OpenGL order (+X, -X, +Y, -Y, +Z, -Z) using the OpenGL cube-map
/// face orientation; texel (i, j) of a face is column i, row j, row 0 at t = -1.
class CubeMap {
 public:
  static constexpr int kFaceCount = 6;

  /// An unrendered cube: background colour and infinite depth. Throws for face_px < 1.
  CubeMap(const glm::dvec3& centre_m, int face_px, const glm::vec3& background);

  const glm::dvec3& centre_m() const { return centre_m_; }
  int face_px() const { return face_px_; }
  /// Unit direction through the centre of texel (i, j) of a face.
  glm::dvec3 texel_direction(int face, int i, int j) const;
  /// Nearest texel in a direction (any length, not zero).
  CubeTexel lookup(const glm::dvec3& direction) const;
  CubeTexel& texel(int face, int i, int j);
  const CubeTexel& texel(int face, int i, int j) const;

 private:
  size_t index(int face, int i, int j) const;

  glm::dvec3 centre_m_;
  int face_px_;
  std::vector<CubeTexel> texels_;
};

/// Renders the six 90-degree faces of face_px x face_px texels from eye_m, honouring
/// options.object_mask (a memory holding a subset of objects), background and threads.
CubeMap render_cube(const RayCaster& caster, const glm::dvec3& eye_m, int face_px, const RenderOptions& options);

}  // namespace latsim::renderer
