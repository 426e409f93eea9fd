#include "latsim/sweep/tables.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <optional>
#include <set>
#include <stdexcept>

#include "latsim/results/run_files.hpp"
#include "latsim/sweep/parallel_for.hpp"
#include "latsim/sweep/results_db.hpp"
#include "latsim/sweep/run_table.hpp"
#include "latsim/sweep/segment.hpp"

namespace latsim::sweep {

namespace fs = std::filesystem;

namespace {

// Claim files of finished runs: left by a process killed between writing a
// summary and removing its claim. Claim names start with the run id.
void remove_finished_claims(const SweepStore& store, const std::set<std::string>& finished) {
  std::error_code ec;
  std::vector<fs::path> leftovers;
  for (fs::directory_iterator it(store.claims_dir(), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const auto dot = name.find('.');
    if (dot == 0 || dot == std::string::npos) continue;  // .clock files belong to live processes
    if (finished.count(name.substr(0, dot))) leftovers.push_back(it->path());
  }
  for (const auto& file : leftovers) fs::remove(file, ec);
}

/// Holds DIR/.tables.lock (flock) while the tables are written: several
/// processes may finish a sweep at once, and each rewrites the same files and
/// clears their temporaries. The kernel drops the lock when its holder dies.
class TablesLock {
 public:
  explicit TablesLock(const fs::path& out_dir) {
    const fs::path file = out_dir / ".tables.lock";
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ >= 0 && ::flock(fd_, LOCK_EX) == 0) return;
    // A file system without locks (NFS mounted nolock): carry on, but say so.
    std::fprintf(stderr, "sweep: warning: cannot lock %s (%s); do not write this sweep's tables from two processes at once\n",
                 file.c_str(), std::strerror(errno));
  }
  TablesLock(const TablesLock&) = delete;
  TablesLock& operator=(const TablesLock&) = delete;
  ~TablesLock() {
    if (fd_ >= 0) ::close(fd_);
  }

 private:
  int fd_ = -1;
};

// A finished run's row, read from its record; nothing, and `error` set, when
// the record is missing or unreadable.
std::optional<RunRow> table_row(const SweepPlan& plan, const SweepStore& store, const StoreIndex& index,
                                StoreIndex::Reader& reader, const SweepRun& run, std::string& error) {
  const auto spot = index.find(run.run_id);
  if (!spot) {
    error = store.store_dir().string() + ": run " + run.run_id + " is marked finished but has no record; delete " +
            (store.out_dir() / "done" / run.run_id).string() + " to run it again";
    return std::nullopt;
  }
  try {
    RunRow row{run.run_id, run.point, run.seed, run.replication, {}};
    // The record's first line is the summary but its scenario.
    scan_summary(reader.read_first_line(*spot), row);
    for (size_t a = 0; a < plan.axes().size(); ++a) row.values.push_back(plan.value(run, a));
    return row;
  } catch (const std::exception& e) {
    // Written with a CRC, so this is damage from outside latsim; say so rather than guess.
    error = store.store_dir().string() + ": the record of run " + run.run_id + " is unreadable (" + e.what() +
            "); delete its mark " + (store.out_dir() / "done" / run.run_id).string() + " to run it again";
    return std::nullopt;
  }
}

}  // namespace

size_t write_tables(const SweepPlan& plan, const SweepStore& store, unsigned threads, size_t& temporaries_removed) {
  const TablesLock lock(store.out_dir());
  // A record without its mark (its writer was killed in between) is of a run
  // that runs again: the tables take the finished runs only.
  const std::set<std::string> finished = store.finished_runs();
  const StoreIndex index(store.store_dir());
  std::vector<std::string> pointers;
  for (const auto& axis : plan.axes()) pointers.push_back(axis.pointer);
  temporaries_removed += store.remove_table_temporaries();
  std::string csv = results_csv_header(pointers, plan.figures());
  const std::vector<HeadlineColumn> columns = table_columns(plan.figures());
  threads = std::max(1u, threads);
  ResultsDbWriter db(store.out_dir() / "results.sqlite", pointers, threads);
  // A chunk of runs at a time, each thread reading a slice of it (inflating
  // the records, scanning them, making their results.csv lines and adding
  // their rows to its part of the database), then the parts merged in plan
  // order: memory holds one chunk whatever the sweep's size, and the
  // database's rows are made on every thread.
  constexpr size_t kChunk = 4096;
  const auto& runs = plan.runs();
  size_t tabled = 0;
  std::vector<std::string> lines;  // each run's results.csv line (empty: not finished)
  std::vector<std::string> errors;
  std::vector<int64_t> positions;  // each run's place in the tables
  std::vector<std::string> part_errors(threads);
  for (size_t begin = 0; begin < runs.size(); begin += kChunk) {
    const size_t n = std::min(kChunk, runs.size() - begin);
    lines.assign(n, {});
    errors.assign(n, {});
    positions.assign(n, -1);
    for (size_t k = 0; k < n; ++k)
      if (finished.count(runs[begin + k].run_id)) positions[k] = static_cast<int64_t>(tabled++);
    parallel_for(threads, threads, [&](size_t part) {
      const auto t = static_cast<unsigned>(part);
      const size_t first = part * n / threads;
      try {
        StoreIndex::Reader reader(index);
        db.begin_part(t);
        for (size_t k = first; k < (part + 1) * n / threads; ++k) {
          if (positions[k] < 0) continue;
          const auto row = table_row(plan, store, index, reader, runs[begin + k], errors[k]);
          if (!row) break;
          append_results_csv_row(lines[k], *row, columns);
          db.add_to_part(t, *row, positions[k]);
        }
        db.end_part(t);
      } catch (const std::exception& e) {
        part_errors[part] = e.what();  // the database failed (a full disk)
      }
    });
    for (const auto* list : {&errors, &part_errors})
      for (const auto& error : *list)
        if (!error.empty()) throw std::runtime_error(error);
    db.merge_parts();
    for (const auto& line : lines) csv += line;
  }
  results::write_file_atomically(store.out_dir() / "results.csv", csv);
  db.commit();
  remove_finished_claims(store, finished);
  return tabled;
}

std::vector<std::string> missing_runs(const SweepPlan& plan, const SweepStore& store, RunClaims& claims) {
  const std::set<std::string> finished = store.finished_runs();
  std::vector<std::string> lines;
  for (const auto& run : plan.runs()) {
    if (finished.count(run.run_id)) continue;
    std::string line = run.run_id + " (" + plan.describe(run) + ")";
    if (const auto holder = claims.holder_of(run.run_id)) line += ": running in " + holder->name();
    lines.push_back(std::move(line));
  }
  return lines;
}

}  // namespace latsim::sweep
