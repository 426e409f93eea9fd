// The one way results reach the file system: atomic writes into the run directory.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace latsim::renderer {
struct ImageRGB;
}

namespace latsim::pipelines {

/// Writes text to `file` atomically: "<file>.tmp.<pid>", flushed, then renamed.
void write_file_atomically(const std::filesystem::path& file, std::string_view bytes);

/// A run's result files, owned by the run. Names are relative to the run
/// directory (subdirectories are made); every write is atomic. A run that
/// keeps no files (no directory) writes nothing, and pipelines can ask first
/// so as to skip work whose only product is a file.
class RunFiles {
 public:
  RunFiles() = default;
  explicit RunFiles(std::filesystem::path dir) : dir_(std::move(dir)) {}

  bool enabled() const { return !dir_.empty(); }
  void write_text(const std::string& name, std::string_view text);
  /// An 8-bit sRGB PNG of a linear image.
  void write_png(const std::string& name, const renderer::ImageRGB& image);
  /// Names written so far, in order.
  const std::vector<std::string>& written() const { return written_; }

 private:
  std::filesystem::path dir_;
  std::vector<std::string> written_;
};

}  // namespace latsim::pipelines
