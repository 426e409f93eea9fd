// Which scene to build: one of the generated scenes or a mesh file.
#pragma once

#include <filesystem>
#include <memory>

#include "latsim/renderer/scene.hpp"
#include "latsim/renderer/scene_generators.hpp"

namespace latsim::renderer {

/// The geometry a scenario asks for, before anything is built or loaded.
struct SceneSpec {
  enum class Type { Gallery, Room, TestPattern, Obj };
  Type type = Type::Gallery;
  GalleryParams gallery;       ///< gallery: its sizes
  std::filesystem::path file;  ///< obj: the mesh file
  /// obj: the mesh as read when the scenario was (so that a bad mesh is the
  /// scenario's error, found by validate); nullptr: read by make_scene.
  std::shared_ptr<const Scene> mesh;
};

/// Builds the scene (an obj scene: a copy of `mesh`, or the file read now).
Scene make_scene(const SceneSpec& spec);

}  // namespace latsim::renderer
