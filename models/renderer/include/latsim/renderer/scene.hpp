// Triangle scenes with per-vertex colours, grouped into named objects.
#pragma once

#include "latsim/renderer/aabb.hpp"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace latsim::renderer {

/// Thrown for malformed scene input; what() names the place, e.g. "room.obj:12: <reason>".
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One triangle: three corners in world metres, each with a linear RGB colour.
struct Triangle {
  std::array<glm::vec3, 3> position_m;
  std::array<glm::vec3, 3> colour;
};

/// A sphere primitive (Pixel-Planes renderers draw spheres natively): centre
/// and radius in world metres, one linear RGB colour. Pipelines that draw
/// triangles only see it tessellated (make_scene, SphereForm::tessellated).
struct Sphere {
  glm::vec3 centre_m{0.0f};
  float radius_m = 0.0f;
  glm::vec3 colour{1.0f};
};

/// A named, contiguous range of the scene's triangles (the unit that models update and cull).
struct SceneObject {
  std::string name;
  uint32_t first_triangle = 0;
  uint32_t triangle_count = 0;
  Aabb bounds;
  bool animated = false;
};

/// A triangle soup partitioned into objects; objects are appended one after
/// another. Spheres, when there are any, stand beside the objects.
class Scene {
 public:
  /// Starts a new object; following add_triangle calls belong to it. Returns its id.
  uint32_t begin_object(std::string name, bool animated = false);
  /// Appends a triangle to the most recently begun object; throws if none was begun.
  void add_triangle(const Triangle& triangle);
  /// Appends a triangle with one colour on all three corners.
  void add_triangle(const glm::vec3& a_m, const glm::vec3& b_m, const glm::vec3& c_m,
                    const glm::vec3& colour);

  /// Appends a sphere (radius above zero; throws SceneError otherwise).
  void add_sphere(const Sphere& sphere);

  const std::vector<Triangle>& triangles() const { return triangles_; }
  const std::vector<Sphere>& spheres() const { return spheres_; }
  const std::vector<SceneObject>& objects() const { return objects_; }
  const Aabb& bounds() const { return bounds_; }
  uint32_t object_count() const { return static_cast<uint32_t>(objects_.size()); }
  uint32_t triangle_count() const { return static_cast<uint32_t>(triangles_.size()); }
  /// Index of the first object with this name; throws SceneError if there is none.
  uint32_t find_object(const std::string& name) const;

 private:
  std::vector<Triangle> triangles_;
  std::vector<Sphere> spheres_;
  std::vector<SceneObject> objects_;
  Aabb bounds_;
};

}  // namespace latsim::renderer
