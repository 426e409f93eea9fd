#include "latsim/renderer/scene.hpp"

#include <limits>

namespace latsim::renderer {

uint32_t Scene::begin_object(std::string name, bool animated) {
  if (triangles_.size() > std::numeric_limits<uint32_t>::max() - 1) {
    throw SceneError("scene: too many triangles for 32-bit indices");
  }
  SceneObject object;
  object.name = std::move(name);
  object.first_triangle = static_cast<uint32_t>(triangles_.size());
  object.animated = animated;
  objects_.push_back(std::move(object));
  return static_cast<uint32_t>(objects_.size() - 1);
}

void Scene::add_triangle(const Triangle& triangle) {
  if (objects_.empty()) {
    throw SceneError("scene: add_triangle called before begin_object; begin an object first");
  }
  triangles_.push_back(triangle);
  SceneObject& object = objects_.back();
  ++object.triangle_count;
  for (const glm::vec3& corner : triangle.position_m) {
    object.bounds.extend(glm::dvec3(corner));
    bounds_.extend(glm::dvec3(corner));
  }
}

void Scene::add_triangle(const glm::vec3& a_m, const glm::vec3& b_m, const glm::vec3& c_m,
                         const glm::vec3& colour) {
  add_triangle(Triangle{{a_m, b_m, c_m}, {colour, colour, colour}});
}

void Scene::add_sphere(const Sphere& sphere) {
  if (!(sphere.radius_m > 0.0f)) throw SceneError("scene: a sphere needs a radius above zero");
  spheres_.push_back(sphere);
  const glm::dvec3 r(sphere.radius_m);
  bounds_.extend(glm::dvec3(sphere.centre_m) - r);
  bounds_.extend(glm::dvec3(sphere.centre_m) + r);
}

uint32_t Scene::find_object(const std::string& name) const {
  for (size_t i = 0; i < objects_.size(); ++i) {
    if (objects_[i].name == name) return static_cast<uint32_t>(i);
  }
  throw SceneError("scene: no object named '" + name + "'");
}

}  // namespace latsim::renderer
