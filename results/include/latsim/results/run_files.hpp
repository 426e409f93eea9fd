// The one way results reach the file system: atomic writes into the run
// directory, which appears whole or not at all.
#pragma once

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace latsim::renderer {
struct ImageRGB;
}

namespace latsim::results {

/// A result file that could not be written: which, and the system's reason.
class WriteError : public std::runtime_error {
 public:
  WriteError(std::filesystem::path file, int error_number);
  const std::filesystem::path& file() const { return file_; }
  int error_number() const { return errno_; }
  /// The storage is full, over quota or not writable: other writes there will
  /// fail too, so a batch of runs should stop rather than try each.
  bool storage_unusable() const;

 private:
  std::filesystem::path file_;
  int errno_;
};

/// Writes bytes to `file` atomically: "<file>.tmp.<pid>", then renamed over
/// `file`. Throws WriteError on any failure, leaving neither `file` changed
/// nor the temporary file behind.
void write_file_atomically(const std::filesystem::path& file, std::string_view bytes);

/// Where a run directory is assembled before commit: "<dir>.tmp.<pid>" beside
/// it (so that the final rename stays on one file system).
std::filesystem::path staging_dir_of(const std::filesystem::path& dir, long pid);

/// A run's summary.json, the one way it is read back: nullopt when there is
/// none (the run has not finished); a file that cannot be parsed was damaged
/// outside latsim (it is written atomically, last), and throws
/// std::runtime_error naming it and ending with `remedy`.
std::optional<nlohmann::json> read_summary(const std::filesystem::path& file, const std::string& remedy);

/// A result file written piece by piece while the run produces it, into the
/// run's staging directory: it reaches the run directory with the other
/// files at RunFiles::commit() once RunFiles::commit(StreamedFile&) has
/// completed it, and is removed with the staging directory otherwise. A
/// default (closed) one ignores writes.
class StreamedFile {
 public:
  StreamedFile() = default;
  StreamedFile(std::filesystem::path staged, std::filesystem::path shown_as);
  StreamedFile(StreamedFile&& o) noexcept;
  StreamedFile& operator=(StreamedFile&& o) noexcept;
  StreamedFile(const StreamedFile&) = delete;
  StreamedFile& operator=(const StreamedFile&) = delete;
  ~StreamedFile();

  bool is_open() const { return out_ != nullptr; }
  /// Throws WriteError (naming the file as the user will look for it).
  void write(std::string_view bytes);

 private:
  friend class RunFiles;
  // Flushes and closes; throws WriteError on failure.
  void close();
  void discard() noexcept;

  std::filesystem::path staged_;    // where it is written
  std::filesystem::path shown_as_;  // its place in the run directory (for messages)
  std::FILE* out_ = nullptr;
  // The stream's buffer: a streamed timeline costs a write call per 64 KiB,
  // not per 4 KiB. (Larger buffers cost more than the calls they save: a
  // run's hot data no longer fits the cache beside them.)
  static constexpr size_t kBufferBytes = size_t{1} << 16;
  std::unique_ptr<char[]> buffer_;
};

/// A run's result files, owned by the run. Names are relative to the run
/// directory (subdirectories are made). Files go to a staging directory
/// beside it and reach the run directory only at commit(): a run that fails,
/// is interrupted or is killed leaves no run directory behind, and the
/// destructor removes the staging directory of a run that did not commit.
/// A run that keeps no files (no directory) writes nothing, and pipelines
/// can ask first so as to skip work whose only product is a file.
class RunFiles {
 public:
  RunFiles() = default;
  /// `staging`: where files wait for commit (default: staging_dir_of(dir, this pid)).
  explicit RunFiles(std::filesystem::path dir, std::filesystem::path staging = {});
  ~RunFiles();
  RunFiles(RunFiles&& other) noexcept;
  RunFiles& operator=(RunFiles&& other) noexcept;
  RunFiles(const RunFiles&) = delete;
  RunFiles& operator=(const RunFiles&) = delete;

  bool enabled() const { return !dir_.empty(); }
  /// Whether write_png writes (default) or drops images: a run kept for its
  /// figures alone still renders and measures what it would capture.
  void set_write_images(bool write) { write_images_ = write; }
  bool writes_images() const { return enabled() && write_images_; }
  const std::filesystem::path& dir() const { return dir_; }
  /// Makes the staging directory now (writes make it too): a place that
  /// cannot be written fails before the simulation rather than after it.
  void prepare();
  void write_text(const std::string& name, std::string_view text);
  /// An 8-bit sRGB PNG of a linear image.
  void write_png(const std::string& name, const renderer::ImageRGB& image);
  /// A file to write as the run goes (a closed one when the run keeps no files).
  StreamedFile stream(const std::string& name);
  /// Completes a streamed file; it is committed with the others.
  void commit(StreamedFile& file, const std::string& name);
  /// Names written so far, in order.
  const std::vector<std::string>& written() const { return written_; }
  /// Moves every file written into the run directory: one rename when the
  /// directory does not exist yet; otherwise file by file, the existing
  /// summary.json removed first and `last` (when written) moved last, so
  /// that the directory counts as complete only once everything is in.
  void commit(const std::string& last = "summary.json");

 private:
  void discard() noexcept;

  std::filesystem::path dir_;
  std::filesystem::path staging_;
  bool staged_ = false;
  bool write_images_ = true;
  std::vector<std::string> written_;
};

}  // namespace latsim::results
