// A capture file read line by line, in pieces, with line numbers.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "latsim/io/input_file.hpp"

namespace latsim::capture {

/// The lines of a regular file of at most kMaxCaptureBytes, streamed in 1 MiB
/// pieces: an optional UTF-8 byte-order mark dropped, LF or CRLF ends.
class LineSource {
 public:
  explicit LineSource(const std::filesystem::path& file);

  /// The next line without its line end (false at the end of the file); the
  /// view lives until the next call.
  bool next(std::string_view& line);
  /// The number of the line last returned (1 for the first).
  int64_t number() const { return number_; }
  const std::filesystem::path& file() const { return file_; }

 private:
  bool finish(std::string_view& line);

  std::filesystem::path file_;
  io::InputFile in_;
  std::string buffer_;
  size_t pos_ = 0;
  int64_t number_ = 0;
};

}  // namespace latsim::capture
