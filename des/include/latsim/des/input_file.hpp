// Reading an input file whole: a scenario, a head-motion trace, a mesh. Only
// a regular file is read, never more than a stated size, so a FIFO, a device
// such as /dev/zero or a runaway file is refused at once instead of hanging
// the program or filling its memory.
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace latsim::des {

/// Why an input file could not be read, in words that follow "cannot read
/// FILE: " (e.g. "it is not a regular file (a device, pipe or socket)").
class InputFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The whole content of regular file `file` of at most `max_bytes`. Opening
/// never blocks (a FIFO without a writer is refused like any other FIFO).
/// Throws InputFileError when the file is missing, unreadable, a directory,
/// device, pipe or socket, or larger than `max_bytes`.
std::string read_input_file(const std::filesystem::path& file, size_t max_bytes);

}  // namespace latsim::des
