#include "latsim/io/line_error.hpp"

namespace latsim::io {

namespace {

std::string located_in(const std::filesystem::path& file, int64_t line, const std::string& reason) {
  std::string text = file.string();
  if (line > 0) text.append(":").append(std::to_string(line));
  return text.append(": ").append(reason);
}

}  // namespace

LineError::LineError(const std::filesystem::path& file, int64_t line, const std::string& reason)
    : std::runtime_error(located_in(file, line, reason)), line_(line) {}

}  // namespace latsim::io
