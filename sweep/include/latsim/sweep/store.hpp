// The on-disk layout of a sweep's output directory, and what makes resuming safe.
#pragma once

#include <filesystem>
#include <set>
#include <string>

namespace latsim::sweep {

/// A sweep output directory. Every finished run's figures and summary are one
/// record in the results store, DIR/store/ (StoreSegment: a file per run
/// thread of each process, appended to and never rewritten), and the run is
/// marked finished by an empty file DIR/done/<run id>, made once its record
/// is written: a hard link to an empty file of its writer's (DIR/done/.mark.*),
/// which takes neither an inode nor a block. Only the runs the keep policy keeps also have a directory,
/// DIR/runs/<run id>/, with summary.json, figures.json and their traces. Any
/// number of processes, on any hosts sharing the directory, may work in it at
/// once: each run is guarded by its claim (RunClaims in DIR/claims/), and
/// each writer appends to segments of its own, so nothing here locks the
/// directory as a whole.
class SweepStore {
 public:
  /// Creates DIR, DIR/runs, DIR/store and DIR/done if needed.
  explicit SweepStore(std::filesystem::path out_dir);

  const std::filesystem::path& out_dir() const { return out_dir_; }
  std::filesystem::path run_dir(const std::string& run_id) const;
  /// Where a kept run's files wait until it commits them: "runs/<id>.tmp",
  /// safe to share by name because only the holder of the run's claim writes there.
  std::filesystem::path staging_dir(const std::string& run_id) const;
  std::filesystem::path claims_dir() const { return out_dir_ / "claims"; }
  std::filesystem::path store_dir() const { return out_dir_ / "store"; }
  /// Whether the run is finished (its record written), as of now.
  bool is_finished(const std::string& run_id) const;
  /// Marks a run finished, once its record is in the store, by linking its
  /// name to `mark` (from new_mark()); false when `mark` has as many links as
  /// the file system allows (EMLINK): make a new one. Throws results::WriteError.
  bool mark_finished(const std::string& run_id, const std::filesystem::path& mark) const;
  /// A new empty file DIR/done/.mark.<name> for mark_finished to link to.
  std::filesystem::path new_mark(const std::string& name) const;
  /// Every run finished so far (one directory listing).
  std::set<std::string> finished_runs() const;
  /// Removes what an interrupted writer of one run left: its staging
  /// directory and temporary files in its run directory. Only for the holder
  /// of the run's claim: nobody else can be writing there. Returns how many
  /// files and directories.
  size_t remove_run_temporaries(const std::string& run_id) const;
  /// Removes temporary files of the top-level tables (results.*, plan.json),
  /// for the process about to write them. Returns how many.
  size_t remove_table_temporaries() const;

 private:
  std::filesystem::path done_file(const std::string& run_id) const { return out_dir_ / "done" / run_id; }

  std::filesystem::path out_dir_;
};

/// The runs marked finished in the sweep directory `out_dir` (none when it
/// is no sweep directory), without creating anything.
std::set<std::string> finished_runs_in(const std::filesystem::path& out_dir);

/// True for names of files still being written: "<name>.tmp" or "<name>.tmp.<digits>".
bool is_temporary_name(const std::string& filename);

/// Writes `text` to `file` atomically unless the file already holds exactly that
/// (several processes starting on one directory write the same plan.json).
void write_file_if_changed(const std::filesystem::path& file, const std::string& text);

}  // namespace latsim::sweep
