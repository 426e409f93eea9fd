// Wavefront OBJ reader producing a Scene.
#pragma once

#include "latsim/renderer/scene.hpp"

#include <glm/vec3.hpp>

#include <filesystem>
#include <cstddef>
#include <istream>
#include <string>

namespace latsim::renderer {

/// Reads "v x y z [w]" and "v x y z r g b" (linear colours), "f" with any number of
/// corners (triangulated as a fan from the first), positive and negative (relative)
/// indices in the i, i/t, i//n and i/t/n forms, and "o"/"g" lines that start a new object.
/// vt, vn, usemtl, mtllib and s lines are ignored; any other statement is an error.
/// Vertices without a colour get default_colour. Faces before any o/g line go to an
/// object named "default". Throws SceneError whose what() is "<source_name>:<line>: <reason>".
Scene parse_obj(std::istream& input, const std::string& source_name,
                const glm::vec3& default_colour = glm::vec3(0.8f));

/// The largest mesh file load_obj reads (as a scenario file may be).
inline constexpr size_t kMaxObjBytes = size_t{16} << 20;

/// Reads and parses an OBJ file; source_name in errors is the path as given.
/// Only a regular file of at most kMaxObjBytes is read: a larger one, a FIFO
/// or a device is a SceneError "<path>: cannot read the mesh: <why>".
Scene load_obj(const std::filesystem::path& path, const glm::vec3& default_colour = glm::vec3(0.8f));

}  // namespace latsim::renderer
