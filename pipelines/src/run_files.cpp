#include "latsim/pipelines/run_files.hpp"

#include <unistd.h>

#include <fstream>
#include <stdexcept>

#include "latsim/renderer/png_writer.hpp"

namespace latsim::pipelines {

void write_file_atomically(const std::filesystem::path& file, std::string_view bytes) {
  const std::filesystem::path tmp = file.string() + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) throw std::runtime_error("error writing " + tmp.string());
  }
  std::filesystem::rename(tmp, file);
}

void RunFiles::write_text(const std::string& name, std::string_view text) {
  if (!enabled()) return;
  const std::filesystem::path file = dir_ / name;
  std::filesystem::create_directories(file.parent_path());
  write_file_atomically(file, text);
  written_.push_back(name);
}

void RunFiles::write_png(const std::string& name, const renderer::ImageRGB& image) {
  if (!enabled()) return;
  const std::vector<uint8_t> bytes = renderer::encode_png(image);
  write_text(name, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace latsim::pipelines
