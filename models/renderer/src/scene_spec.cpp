#include "latsim/renderer/scene_spec.hpp"

#include "latsim/renderer/obj_loader.hpp"

namespace latsim::renderer {

Scene make_scene(const SceneSpec& spec) {
  switch (spec.type) {
    case SceneSpec::Type::Room:
      return make_room();
    case SceneSpec::Type::TestPattern:
      return make_test_pattern();
    case SceneSpec::Type::Obj:
      return spec.mesh ? *spec.mesh : load_obj(spec.file);
    case SceneSpec::Type::Gallery:
      break;
  }
  return make_gallery(spec.gallery);
}

}  // namespace latsim::renderer
