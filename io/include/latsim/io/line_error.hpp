// A problem at a line of an input file (a head-motion trace, a capture),
// located the way compilers locate theirs so that an editor can jump to it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace latsim::io {

/// An input file that cannot be used; what() is exactly "<file>:<line>: <reason>"
/// ("<file>: <reason>" for a problem of the whole file, line 0).
class LineError : public std::runtime_error {
 public:
  LineError(const std::filesystem::path& file, int64_t line, const std::string& reason);
  int64_t line() const { return line_; }

 private:
  int64_t line_;
};

}  // namespace latsim::io
