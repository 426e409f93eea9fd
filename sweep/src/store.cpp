#include "latsim/results/run_files.hpp"
#include "latsim/sweep/store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>


namespace latsim::sweep {

namespace fs = std::filesystem;

SweepStore::SweepStore(fs::path out_dir) : out_dir_(std::move(out_dir)) {
  fs::create_directories(out_dir_ / "runs");
  fs::create_directories(out_dir_ / "store");
  fs::create_directories(out_dir_ / "done");
}

fs::path SweepStore::run_dir(const std::string& run_id) const { return out_dir_ / "runs" / run_id; }

fs::path SweepStore::staging_dir(const std::string& run_id) const { return out_dir_ / "runs" / (run_id + ".tmp"); }

bool SweepStore::is_finished(const std::string& run_id) const { return ::access(done_file(run_id).c_str(), F_OK) == 0; }

bool SweepStore::mark_finished(const std::string& run_id, const fs::path& mark) const {
  const fs::path file = done_file(run_id);
  if (::link(mark.c_str(), file.c_str()) == 0 || errno == EEXIST) return true;
  if (errno == EMLINK) return false;
  throw results::WriteError(file, errno);
}

fs::path SweepStore::new_mark(const std::string& name) const {
  const fs::path file = out_dir_ / "done" / (".mark." + name);
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw results::WriteError(file, errno);
  ::close(fd);
  return file;
}

std::set<std::string> SweepStore::finished_runs() const { return finished_runs_in(out_dir_); }

std::set<std::string> finished_runs_in(const fs::path& out_dir) {
  std::set<std::string> done;
  std::error_code ec;
  for (fs::directory_iterator it(out_dir / "done", ec), end; !ec && it != end; it.increment(ec)) {
    std::string name = it->path().filename().string();
    if (name[0] != '.') done.insert(std::move(name));  // .mark.* are what the marks link to
  }
  return done;
}

size_t SweepStore::remove_run_temporaries(const std::string& run_id) const {
  std::vector<fs::path> stale;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(run_dir(run_id), ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file() && is_temporary_name(it->path().filename().string())) stale.push_back(it->path());
  for (const auto& file : stale) fs::remove(file);
  const bool staged = fs::exists(staging_dir(run_id), ec);
  if (staged) fs::remove_all(staging_dir(run_id));
  return stale.size() + (staged ? 1 : 0);
}

size_t SweepStore::remove_table_temporaries() const {
  // Only what a sweep writes at the top; other files in a directory the user
  // chose are none of our business.
  std::vector<fs::path> stale;
  for (const auto& entry : fs::directory_iterator(out_dir_)) {
    const std::string name = entry.path().filename().string();
    const bool ours = name.rfind("results.", 0) == 0 || name.rfind("plan.json", 0) == 0;
    if (ours && entry.is_regular_file() && is_temporary_name(name)) stale.push_back(entry.path());
  }
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

void write_file_if_changed(const fs::path& file, const std::string& text) {
  std::ifstream in(file, std::ios::binary);
  if (in) {
    std::stringstream buf;
    buf << in.rdbuf();
    if (buf.str() == text) return;
  }
  results::write_file_atomically(file, text);
}

}  // namespace latsim::sweep
