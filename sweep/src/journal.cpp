#include "latsim/sweep/journal.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

namespace latsim::sweep {

namespace fs = std::filesystem;

SweepJournal::SweepJournal(const fs::path& out_dir, const std::string& host, long pid)
    : file_(out_dir / "journal" / (host + "." + std::to_string(pid) + ".log")) {
  fs::create_directories(file_.parent_path());
  fd_ = ::open(file_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error(file_.string() + ": cannot open the journal: " + std::strerror(errno));
}

SweepJournal::~SweepJournal() {
  if (fd_ >= 0) ::close(fd_);
}

void SweepJournal::record(const std::string& event, const std::string& run_id, const std::string& detail) const {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                      std::chrono::system_clock::now().time_since_epoch()).count();
  std::string line = std::to_string(ms) + " " + event + " " + run_id;
  if (!detail.empty()) line += " " + detail;
  for (char& c : line)
    if (c == '\n') c = ' ';
  line += '\n';
  if (::write(fd_, line.data(), line.size()) != static_cast<ssize_t>(line.size()))
    throw std::runtime_error(file_.string() + ": cannot append to the journal: " + std::strerror(errno));
}

}  // namespace latsim::sweep
