// The on-disk layout of a sweep's output directory, and what makes resuming safe.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace latsim::sweep {

/// A sweep output directory: DIR/runs/<run id>/ per run, a run being finished
/// exactly when its summary.json exists (the runner writes it last,
/// atomically). Any number of processes, on any hosts sharing the directory,
/// may work in it at once: each run is guarded by its claim (RunClaims in
/// DIR/claims/), so nothing here locks the directory as a whole.
class SweepStore {
 public:
  /// Creates DIR and DIR/runs if needed.
  explicit SweepStore(std::filesystem::path out_dir);

  const std::filesystem::path& out_dir() const { return out_dir_; }
  std::filesystem::path run_dir(const std::string& run_id) const;
  /// Where a run's files wait until it commits them: "runs/<id>.tmp", safe to
  /// share by name because only the holder of the run's claim writes there.
  std::filesystem::path staging_dir(const std::string& run_id) const;
  std::filesystem::path summary_file(const std::string& run_id) const;
  std::filesystem::path claims_dir() const { return out_dir_ / "claims"; }
  bool is_finished(const std::string& run_id) const;
  /// The run's summary.json, or empty when the run is not finished.
  std::optional<nlohmann::json> load_summary(const std::string& run_id) const;
  /// Removes what an interrupted writer of one run left: its staging
  /// directory and temporary files in its run directory. Only for the holder
  /// of the run's claim: nobody else can be writing there. Returns how many
  /// files and directories.
  size_t remove_run_temporaries(const std::string& run_id) const;
  /// Removes temporary files of the top-level tables (results.*, plan.json),
  /// for the process about to write them. Returns how many.
  size_t remove_table_temporaries() const;

 private:
  std::filesystem::path out_dir_;
};

/// True for names of files still being written: "<name>.tmp" or "<name>.tmp.<digits>".
bool is_temporary_name(const std::string& filename);

/// Writes `text` to `file` atomically unless the file already holds exactly that
/// (several processes starting on one directory write the same plan.json).
void write_file_if_changed(const std::filesystem::path& file, const std::string& text);

}  // namespace latsim::sweep
