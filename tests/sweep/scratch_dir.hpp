// A fresh scratch directory per test process, for tests that write files.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

namespace latsim::test {

/// TMPDIR/<name>_<pid>, emptied and created; the pid keeps parallel test processes apart.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace latsim::test
