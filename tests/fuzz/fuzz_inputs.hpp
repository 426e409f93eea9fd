// What the fuzz targets share: a private directory that mirrors the shipped
// scenarios (so inputs may include or name them) and a place to put an input
// that must be read from a file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

namespace latsim::fuzz {

/// A per-process directory holding symbolic links to every file and
/// directory of scenarios/, and at its top level also to every file of its
/// subdirectories (first one wins), so that "include": "base.json" or
/// "file": "user1_quaternion.txt" in an input written there finds a file.
/// Removed at exit.
const std::filesystem::path& mirror_dir();

/// Writes the input to `name` in mirror_dir() and returns its path.
std::filesystem::path write_input(std::string_view name, const uint8_t* data, size_t size);

}  // namespace latsim::fuzz
