#include "sweep_store.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace latsim::app {

namespace fs = std::filesystem;

SweepStore::SweepStore(fs::path out_dir) : out_dir_(std::move(out_dir)) {
  fs::create_directories(out_dir_ / "runs");
  const fs::path lock_file = out_dir_ / ".sweep.lock";
  lock_fd_ = ::open(lock_file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0) throw std::runtime_error(lock_file.string() + ": cannot open the lock file");
  // The kernel drops the lock when the process dies, even by kill -9.
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(lock_fd_);
    throw std::runtime_error(out_dir_.string() + ": another sweep is writing to this directory; wait for it or use another --out");
  }
}

SweepStore::~SweepStore() {
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

fs::path SweepStore::run_dir(const std::string& run_id) const { return out_dir_ / "runs" / run_id; }

fs::path SweepStore::summary_file(const std::string& run_id) const { return run_dir(run_id) / "summary.json"; }

bool SweepStore::is_finished(const std::string& run_id) const { return fs::exists(summary_file(run_id)); }

std::optional<nlohmann::json> SweepStore::load_summary(const std::string& run_id) const {
  const fs::path file = summary_file(run_id);
  std::ifstream in(file);
  if (!in) return std::nullopt;
  std::stringstream buf;
  buf << in.rdbuf();
  try {
    return nlohmann::json::parse(buf.str());
  } catch (const nlohmann::json::parse_error& e) {
    // Written atomically, so this is damage from outside latsim; say so rather than guess.
    throw std::runtime_error(file.string() + ": unreadable summary (" + e.what() + "); delete it to run this point again");
  }
}

size_t SweepStore::remove_temporaries() const {
  // Only what a sweep writes: its own tables at the top, anything under runs/;
  // other files in a directory the user chose are none of our business.
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(out_dir_)) {
    const std::string name = entry.path().filename().string();
    const bool ours = name.rfind("results.", 0) == 0 || name.rfind("plan.json", 0) == 0;
    if (ours && entry.is_regular_file() && is_temporary_name(name)) stale.push_back(entry.path());
  }
  for (const auto& entry : fs::recursive_directory_iterator(out_dir_ / "runs"))
    if (entry.is_regular_file() && is_temporary_name(entry.path().filename().string())) stale.push_back(entry.path());
  for (const auto& file : stale) fs::remove(file);
  return stale.size();
}

bool is_temporary_name(const std::string& filename) {
  const auto pos = filename.rfind(".tmp");
  if (pos == std::string::npos || pos == 0) return false;
  const std::string rest = filename.substr(pos + 4);
  if (rest.empty()) return true;
  if (rest[0] != '.' || rest.size() == 1) return false;
  for (size_t i = 1; i < rest.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(rest[i]))) return false;
  return true;
}

}  // namespace latsim::app
