// results.sqlite: every figure of every run of a sweep, for ad-hoc queries.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "latsim/sweep/run_table.hpp"

namespace latsim::sweep {

/// Writes `file` atomically (a temporary database, then rename) with tables
///   axes(axis, pointer)
///   runs(run_id, plan_index, point, seed, replication, events, wall_s, peak_rss_mb, fingerprint, "<axis pointer>"...)
/// and views over compact tables of integer ids (names; figure_values,
/// distribution_values with one row per distribution, model_values):
///   figures(run_id, name, value)                 scalar figures by dotted name
///   distributions(run_id, name, stat, value)     count, mean, p99, ... of each distribution
///   models(run_id, model, events, wall_s)
/// Histograms are not in it: each run's are in its record in the results
/// store (and its summary.json when kept), where the report reads them.
/// Throws std::runtime_error naming the file on any SQLite failure.
void write_results_db(const std::filesystem::path& file, const std::vector<std::string>& axis_pointers,
                      const std::vector<RunRow>& rows);

/// write_results_db a chunk of runs at a time, so that a sweep of any size is
/// written with only a chunk in memory, and by many threads: each thread adds
/// its runs to a part of its own (a database beside the file, written apart),
/// and merge_parts() moves the parts' rows into the database, part 0 first,
/// in SQLite's own bulk copy. Positions are the runs' places in the tables.
/// commit() renames the database into place; destroyed uncommitted, it
/// leaves nothing.
class ResultsDbWriter {
 public:
  ResultsDbWriter(std::filesystem::path file, const std::vector<std::string>& axis_pointers, unsigned parts = 0);
  ~ResultsDbWriter();
  ResultsDbWriter(const ResultsDbWriter&) = delete;
  ResultsDbWriter& operator=(const ResultsDbWriter&) = delete;

  /// Adds a run to the database itself (one thread).
  void add(const RunRow& row, int64_t position);
  /// A part's rows between begin_part and end_part, from one thread per part.
  void begin_part(unsigned part);
  void add_to_part(unsigned part, const RunRow& row, int64_t position);
  void end_part(unsigned part);
  /// Moves every part's rows into the database (no part may be between begin and end).
  void merge_parts();
  void commit();

 private:
  struct Open;
  std::filesystem::path part_file(unsigned k) const;
  void remove_files();

  std::filesystem::path file_, temp_;
  std::unique_ptr<Open> open_;
};

}  // namespace latsim::sweep
