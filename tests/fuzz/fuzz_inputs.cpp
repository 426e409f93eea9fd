#include "fuzz_inputs.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <vector>
#include <fstream>
#include <string>

namespace latsim::fuzz {

namespace fs = std::filesystem;

namespace {

// Sorted, so that which of two same-named files is linked flat is always the same.
std::vector<fs::path> sorted_entries(const fs::path& dir, bool recursive) {
  std::vector<fs::path> out;
  if (recursive) {
    for (const auto& e : fs::recursive_directory_iterator(dir))
      if (e.is_regular_file()) out.push_back(e.path());
  } else {
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

void link_tree(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  for (const auto& entry : sorted_entries(from, false)) fs::create_symlink(entry, to / entry.filename(), ec);
  // Also flat at the top, where inputs are written (a name taken stays taken).
  for (const auto& file : sorted_entries(from, true)) fs::create_symlink(file, to / file.filename(), ec);
}

struct Mirror {
  fs::path dir;
  Mirror() {
    dir = fs::temp_directory_path() / ("latsim_fuzz." + std::to_string(::getpid()));
    fs::create_directories(dir);
    link_tree(fs::path(LATSIM_SOURCE_DIR) / "scenarios", dir);
  }
  ~Mirror() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

}  // namespace

const fs::path& mirror_dir() {
  static const Mirror mirror;
  return mirror.dir;
}

fs::path write_input(std::string_view name, const uint8_t* data, size_t size) {
  const fs::path file = mirror_dir() / std::string(name);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file;
}

}  // namespace latsim::fuzz
