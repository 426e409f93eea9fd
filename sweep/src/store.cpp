#include "latsim/results/run_files.hpp"
#include "latsim/sweep/store.hpp"

#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "latsim/run/runner.hpp"

namespace latsim::sweep {

namespace fs = std::filesystem;

SweepStore::SweepStore(fs::path out_dir) : out_dir_(std::move(out_dir)) { fs::create_directories(out_dir_ / "runs"); }

fs::path SweepStore::run_dir(const std::string& run_id) const { return out_dir_ / "runs" / run_id; }

fs::path SweepStore::staging_dir(const std::string& run_id) const { return out_dir_ / "runs" / (run_id + ".tmp"); }

fs::path SweepStore::summary_file(const std::string& run_id) const { return run_dir(run_id) / "summary.json"; }

bool SweepStore::is_finished(const std::string& run_id) const { return fs::exists(summary_file(run_id)); }

std::optional<nlohmann::json> SweepStore::load_summary(const std::string& run_id) const {
  return results::read_summary(summary_file(run_id), "delete it to run this point again");
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
