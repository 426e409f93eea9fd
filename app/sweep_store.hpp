// The on-disk layout of a sweep's output directory, and what makes resuming safe.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace latsim::app {

/// A sweep output directory: DIR/runs/<run id>/ per run, a run being finished
/// exactly when its summary.json exists (the runner writes it last, atomically).
/// Holds an exclusive lock on the directory so two sweeps cannot interleave.
class SweepStore {
 public:
  /// Creates DIR and DIR/runs if needed and locks DIR; throws std::runtime_error
  /// when another process holds the lock.
  explicit SweepStore(std::filesystem::path out_dir);
  SweepStore(const SweepStore&) = delete;
  SweepStore& operator=(const SweepStore&) = delete;
  ~SweepStore();

  const std::filesystem::path& out_dir() const { return out_dir_; }
  std::filesystem::path run_dir(const std::string& run_id) const;
  std::filesystem::path summary_file(const std::string& run_id) const;
  bool is_finished(const std::string& run_id) const;
  /// The run's summary.json, or empty when the run is not finished.
  std::optional<nlohmann::json> load_summary(const std::string& run_id) const;
  /// Removes temporary files an interrupted writer left behind, under runs/
  /// and of the top-level tables (safe: we hold the lock, and a temporary file
  /// is never a finished result). Returns how many.
  size_t remove_temporaries() const;

 private:
  std::filesystem::path out_dir_;
  int lock_fd_ = -1;
};

/// True for names of files still being written: "<name>.tmp" or "<name>.tmp.<digits>".
bool is_temporary_name(const std::string& filename);

}  // namespace latsim::app
