#include "latsim/renderer/scene_spec.hpp"

#include "latsim/renderer/mesh_builder.hpp"
#include "latsim/renderer/obj_loader.hpp"
#include "latsim/renderer/published_models.hpp"

namespace latsim::renderer {

namespace {

Scene build(const SceneSpec& spec) {
  switch (spec.type) {
    case SceneSpec::Type::Room:
      return make_room();
    case SceneSpec::Type::TestPattern:
      return make_test_pattern();
    case SceneSpec::Type::Obj:
      return spec.mesh ? *spec.mesh : load_obj(spec.file);
    case SceneSpec::Type::Mig:
      return make_mig(spec.model_size_m);
    case SceneSpec::Type::Molecules:
      return make_molecules(spec.model_size_m);
    case SceneSpec::Type::Head:
      return make_head(spec.model_size_m);
    case SceneSpec::Type::Gallery:
      break;
  }
  return make_gallery(spec.gallery);
}

}  // namespace

Scene make_scene(const SceneSpec& spec, SphereForm spheres) {
  Scene scene = build(spec);
  if (spheres == SphereForm::native || scene.spheres().empty()) return scene;
  return tessellate_spheres(scene);
}

}  // namespace latsim::renderer
