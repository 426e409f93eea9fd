#include "latsim/io/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace latsim::io {

InputFile::InputFile(const std::filesystem::path& file, size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO nobody writes to must not hang; it is refused below anyway.
  fd_ = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd_ < 0) throw InputFileError(std::strerror(errno));
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw InputFileError(S_ISDIR(st.st_mode) ? "it is a directory" : "it is not a regular file (a device, pipe or socket)");
  }
  if (static_cast<uint64_t>(st.st_size) > max_bytes) {
    ::close(fd_);
    throw InputFileError("it is too large (" + std::to_string(st.st_size) + " bytes; at most " +
                         std::to_string(max_bytes) + ")");
  }
  size_bytes_ = static_cast<uint64_t>(st.st_size);
}

InputFile::~InputFile() { ::close(fd_); }

size_t InputFile::read(char* buf, size_t n) {
  // Never past the size checked at opening: a file that grows is read as it was.
  const uint64_t left = size_bytes_ - consumed_;
  if (n > left) n = static_cast<size_t>(left);
  if (n == 0) return 0;
  for (;;) {
    const ssize_t got = ::read(fd_, buf, n);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw InputFileError(std::strerror(errno));
    consumed_ += static_cast<uint64_t>(got);
    return static_cast<size_t>(got);
  }
}

std::string read_input_file(const std::filesystem::path& file, size_t max_bytes) {
  InputFile in(file, max_bytes);
  std::string text(static_cast<size_t>(in.size_bytes()), '\0');
  size_t got = 0;
  while (got < text.size()) {
    const size_t n = in.read(text.data() + got, text.size() - got);
    if (n == 0) break;  // shrank while being read: take what is there
    got += n;
  }
  text.resize(got);
  return text;
}

}  // namespace latsim::io
