// Per-run claims in a shared sweep directory, so that processes on any number
// of hosts can work on one sweep without ever running a run twice at once.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

namespace latsim::sweep {

/// A process that holds (or held) a claim, as written in its claim file.
struct ClaimHolder {
  std::string host;      ///< host name
  std::string host_key;  ///< boot id and pid namespace: equal keys share one pid space
  int64_t pid = 0;
  uint64_t pid_start = 0;  ///< the process's start time in clock ticks after boot (0: unknown); guards against pid reuse

  /// This process.
  static ClaimHolder self();
  nlohmann::json to_json() const;
  static ClaimHolder from_json(const nlohmann::json& j);
  /// "host:pid", as messages name a holder.
  std::string name() const;
};

/// Whether a process on this host with this pid and start time still runs.
bool process_alive(int64_t pid, uint64_t pid_start);

/// Why a claim is stale, or nothing when it must be respected. Same host
/// (equal host name and host key): stale exactly when the holder's process is
/// gone (`alive` answers). Any other host: stale when the claim's heartbeat
/// (its modification time) is older than `stale_after_s`.
std::optional<std::string> stale_reason(const ClaimHolder& holder, const ClaimHolder& me, double heartbeat_age_s,
                                        double stale_after_s,
                                        const std::function<bool(int64_t, uint64_t)>& alive = process_alive);

/// What claim() found.
struct ClaimOutcome {
  enum class Kind { taken, retaken, busy } kind = Kind::busy;
  ClaimHolder other;   ///< retaken: the dead holder; busy: the live one
  std::string reason;  ///< retaken: why the old claim was judged stale
};

/// The claims of one sweep directory, DIR/claims/<run id>.<generation>. A
/// claim is taken by linking a complete claim file to its name, which fails
/// when the name exists (atomic on local file systems and NFS alike), so
/// exactly one process holds a run. The file linked is the worker's own
/// holder file, DIR/claims/.holder.<host>.<pid>.<n>.<worker>, written once:
/// a claim makes and removes a name, never a file, because file systems make
/// inodes slowly when many were just freed (ext4 skips recently freed ones).
/// A stale claim is never removed to be retaken: the next generation's name
/// is claimed instead, which again only one process can do. A background
/// thread refreshes the modification time of every claim held (the heartbeat
/// other hosts judge staleness by) every tenth of `stale_after`, at least
/// every second and at most every minute.
class RunClaims {
 public:
  RunClaims(std::filesystem::path claims_dir, std::chrono::seconds stale_after);
  RunClaims(const RunClaims&) = delete;
  RunClaims& operator=(const RunClaims&) = delete;
  /// Stops the heartbeat and releases every claim still held.
  ~RunClaims();

  /// Tries to claim a run for `worker`, which holds one claim at a time;
  /// thread-safe (one thread per worker).
  ClaimOutcome claim(const std::string& run_id, unsigned worker = 0);
  /// Gives a held claim back. A finished run's claims are removed (nobody
  /// needs them: a run is claimed only to be run, and never once finished);
  /// otherwise the claim is marked released, so the run can be claimed again.
  void release(const std::string& run_id, bool run_finished);
  /// The live holder of a run's newest claim, if any (for naming missing runs).
  std::optional<ClaimHolder> holder_of(const std::string& run_id);

  /// Removes the claim files of a finished run (left by a process killed after
  /// its summary was written, or by one that found the run finished).
  void remove_leftovers(const std::string& run_id);

  const std::filesystem::path& dir() const { return dir_; }
  std::chrono::seconds stale_after() const { return stale_after_; }

 private:
  std::filesystem::path claim_file(const std::string& run_id, uint64_t generation) const;
  /// The worker's holder file, written on first use.
  std::filesystem::path holder_file(unsigned worker);
  bool try_link(const std::filesystem::path& file, const std::string& run_id, uint64_t generation, unsigned worker);
  /// Seconds since the file's modification time, by the file system's own clock.
  std::optional<double> heartbeat_age_s(const std::filesystem::path& file);
  void heartbeat_loop();

  std::filesystem::path dir_;
  std::chrono::seconds stale_after_;
  ClaimHolder me_;
  std::mutex mutex_;
  std::map<std::string, uint64_t> held_;  ///< run id -> generation held
  uint64_t serial_;                         ///< this object among the process's claims
  std::map<unsigned, std::filesystem::path> holders_;  ///< worker -> its holder file
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread heartbeat_;
};

}  // namespace latsim::sweep
