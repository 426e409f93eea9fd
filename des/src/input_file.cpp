#include "latsim/des/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace latsim::des {

std::string read_input_file(const std::filesystem::path& file, size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO nobody writes to must not hang; it is refused below anyway.
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw InputFileError(std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw InputFileError(S_ISDIR(st.st_mode) ? "it is a directory" : "it is not a regular file (a device, pipe or socket)");
  }
  if (static_cast<uint64_t>(st.st_size) > max_bytes) {
    ::close(fd);
    throw InputFileError("it is too large (" + std::to_string(st.st_size) + " bytes; at most " +
                         std::to_string(max_bytes) + ")");
  }
  std::string text(static_cast<size_t>(st.st_size), '\0');
  size_t got = 0;
  while (got < text.size()) {
    const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int e = errno;
      ::close(fd);
      throw InputFileError(std::strerror(e));
    }
    if (n == 0) break;  // shrank while being read: take what is there
    got += static_cast<size_t>(n);
  }
  ::close(fd);
  text.resize(got);
  return text;
}

}  // namespace latsim::des
