// Reading an input file whole: a scenario, a head-motion trace, a mesh. Only
// a regular file is read, never more than a stated size, so a FIFO, a device
// such as /dev/zero or a runaway file is refused at once instead of hanging
// the program or filling its memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace latsim::io {

/// Why an input file could not be read, in words that follow "cannot read
/// FILE: " (e.g. "it is not a regular file (a device, pipe or socket)").
class InputFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A regular file of at most a stated size, opened for reading piece by
/// piece (a capture streamed row by row); the checks of read_input_file.
class InputFile {
 public:
  /// Opens `file` without blocking; throws InputFileError as read_input_file does.
  InputFile(const std::filesystem::path& file, size_t max_bytes);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  /// Reads up to `n` bytes into `buf`, never past the size the file had when
  /// opened; 0 at the end. Throws InputFileError on a read error.
  size_t read(char* buf, size_t n);
  /// The size the file had when it was opened.
  uint64_t size_bytes() const { return size_bytes_; }

 private:
  int fd_ = -1;
  uint64_t size_bytes_ = 0;
  uint64_t consumed_ = 0;
};

/// The whole content of regular file `file` of at most `max_bytes`. Opening
/// never blocks (a FIFO without a writer is refused like any other FIFO).
/// Throws InputFileError when the file is missing, unreadable, a directory,
/// device, pipe or socket, or larger than `max_bytes`.
std::string read_input_file(const std::filesystem::path& file, size_t max_bytes);

}  // namespace latsim::io
