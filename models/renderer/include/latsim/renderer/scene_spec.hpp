// Which scene to build: one of the generated scenes or a mesh file.
#pragma once

#include <filesystem>
#include <memory>

#include "latsim/renderer/scene.hpp"
#include "latsim/renderer/scene_generators.hpp"

namespace latsim::renderer {

/// The geometry a scenario asks for, before anything is built or loaded.
struct SceneSpec {
  enum class Type { Gallery, Room, TestPattern, Obj, Mig, Molecules, Head };
  Type type = Type::Gallery;
  GalleryParams gallery;       ///< gallery: its sizes
  double model_size_m = 1.0;   ///< mig: length; molecules: diameter; head: height
  std::filesystem::path file;  ///< obj: the mesh file
  /// obj: the mesh as read when the scenario was (so that a bad mesh is the
  /// scenario's error, found by validate); nullptr: read by make_scene.
  std::shared_ptr<const Scene> mesh;
};

/// How a scene's spheres reach its user.
enum class SphereForm {
  tessellated,  ///< as triangles (tessellate_spheres): for what draws triangles only
  native,       ///< as spheres (Pixel-Planes 5 draws them as primitives of their own)
};

/// Builds the scene (an obj scene: a copy of `mesh`, or the file read now).
Scene make_scene(const SceneSpec& spec, SphereForm spheres = SphereForm::tessellated);

}  // namespace latsim::renderer
