// Which scene to build: one of the generated scenes or a mesh file.
#pragma once

#include <filesystem>

#include "latsim/renderer/scene.hpp"
#include "latsim/renderer/scene_generators.hpp"

namespace latsim::renderer {

/// The geometry a scenario asks for, before anything is built or loaded.
struct SceneSpec {
  enum class Type { Gallery, Room, TestPattern, Obj };
  Type type = Type::Gallery;
  GalleryParams gallery;       ///< gallery: its sizes
  std::filesystem::path file;  ///< obj: the mesh file
};

/// Builds (or loads) the scene.
Scene make_scene(const SceneSpec& spec);

}  // namespace latsim::renderer
