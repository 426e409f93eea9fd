// An append-only record of what one process did in a sweep directory.
#pragma once

#include <filesystem>
#include <string>

namespace latsim::sweep {

/// DIR/journal/<host>.<pid>.log: one line per event, "<unix ms> <event>
/// <run id>[ <detail>]", events start, finish, fail, stop (ended by a signal), skip (found finished after
/// claiming), busy (claimed by a live process) and retake (a stale claim taken
/// over). Each process appends only to its own file, so lines never interleave,
/// even over NFS; counting start lines over all files tells how often each run
/// was started.
class SweepJournal {
 public:
  SweepJournal(const std::filesystem::path& out_dir, const std::string& host, long pid);
  SweepJournal(const SweepJournal&) = delete;
  SweepJournal& operator=(const SweepJournal&) = delete;
  ~SweepJournal();

  /// Appends one line; thread-safe (a single write(2) to an O_APPEND file).
  void record(const std::string& event, const std::string& run_id, const std::string& detail = {}) const;
  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
  int fd_ = -1;
};

}  // namespace latsim::sweep
