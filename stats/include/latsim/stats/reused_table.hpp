// Fixed-size tables that outlive the caches holding them, reused thread by thread.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace latsim::stats {

/// A table of N entries for a cache whose entries are pure functions of
/// their keys (so that an entry left by an earlier owner is as good as a
/// fresh one): taken from a pool of the current thread when the owner is
/// made and given back when it goes. A run makes its caches afresh, and a
/// sweep makes thousands of runs: without the pool each would allocate and
/// zero its tables (about 1 MB a run), which costs page faults and takes the
/// process-wide lock of the memory map that every thread waits on.
template <class Entry, size_t N>
class ReusedTable {
 public:
  ReusedTable() : table_(take()) {}
  ~ReusedTable() {
    if (table_) spares().push_back(std::move(table_));
  }
  ReusedTable(const ReusedTable&) = delete;
  ReusedTable& operator=(const ReusedTable&) = delete;

  Entry& operator[](size_t i) { return (*table_)[i]; }
  static constexpr size_t size() { return N; }

 private:
  using Table = std::vector<Entry>;
  static std::vector<std::unique_ptr<Table>>& spares() {
    thread_local std::vector<std::unique_ptr<Table>> pool;
    return pool;
  }
  static std::unique_ptr<Table> take() {
    auto& pool = spares();
    if (pool.empty()) return std::make_unique<Table>(N);
    auto table = std::move(pool.back());
    pool.pop_back();
    return table;
  }

  std::unique_ptr<Table> table_;
};

}  // namespace latsim::stats
