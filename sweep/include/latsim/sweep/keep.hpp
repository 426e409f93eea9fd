// Which runs of a sweep keep their trace files (timeline, captured frames,
// ledger, samples) besides the figures every run keeps.
#pragma once

#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>

namespace latsim::sweep {

/// The --keep choice (or the sweep file's "keep" key): every run writes
/// figures.json and summary.json; only the runs chosen here also write the
/// traces their scenario and flags ask for.
struct KeepPolicy {
  enum class Kind {
    figures,  ///< no run keeps traces (the default)
    first,    ///< replication 0 of each point
    all,      ///< every run
    runs,     ///< the runs at the listed plan positions
  };
  Kind kind = Kind::figures;
  std::set<size_t> run_indices;  ///< Kind::runs: plan positions, from 0

  /// "figures", "first", "all" or "runs=I,J,..." (plan positions from 0);
  /// throws std::invalid_argument saying what is wrong and what is expected.
  static KeepPolicy parse(std::string_view text);
  /// Throws std::invalid_argument when a listed run is not among `run_count`.
  void check_runs(size_t run_count) const;
  /// Whether the run at plan position `index`, replication `replication`, keeps its traces.
  bool keeps_traces(size_t index, uint64_t replication) const;
  /// The text parse() reads back.
  std::string text() const;
};

}  // namespace latsim::sweep
