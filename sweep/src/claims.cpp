#include "latsim/sweep/claims.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace latsim::sweep {

namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  if (!in) return {};
  std::stringstream buf;
  buf << in.rdbuf();
  return buf.str();
}

std::string trimmed(std::string text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  return text;
}

// Field 22 of /proc/<pid>/stat, counted after the command name's closing
// parenthesis because the name itself may hold spaces and parentheses.
uint64_t start_ticks_of(int64_t pid) {
  const std::string stat = read_text("/proc/" + std::to_string(pid) + "/stat");
  const auto close = stat.rfind(')');
  if (close == std::string::npos) return 0;
  std::istringstream fields(stat.substr(close + 1));
  std::string field;
  for (int i = 3; i <= 22 && fields >> field; ++i)
    if (i == 22) return std::strtoull(field.c_str(), nullptr, 10);
  return 0;
}

double seconds_between(const struct timespec& later, const struct timespec& earlier) {
  return static_cast<double>(later.tv_sec - earlier.tv_sec) + 1e-9 * static_cast<double>(later.tv_nsec - earlier.tv_nsec);
}

// The claim record in a claim file, or nothing when it cannot be read (gone, or damaged).
std::optional<Json> read_record(const fs::path& file) {
  const std::string text = read_text(file);
  if (text.empty()) return std::nullopt;
  try {
    return Json::parse(text);
  } catch (const Json::parse_error&) {
    return Json::object();  // damaged: judged by its heartbeat like a claim from another host
  }
}

// Writes `text` to a new file (failing if it exists) and flushes it.
bool create_file(const fs::path& file, const std::string& text) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return false;
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  ::close(fd);
  return ok;
}

}  // namespace

ClaimHolder ClaimHolder::self() {
  ClaimHolder me;
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) == 0) me.host = name;
  if (me.host.empty()) me.host = "localhost";
  std::error_code ec;
  const auto ns = fs::read_symlink("/proc/self/ns/pid", ec);
  me.host_key = trimmed(read_text("/proc/sys/kernel/random/boot_id")) + "/" + (ec ? std::string() : ns.string());
  me.pid = ::getpid();
  me.pid_start = start_ticks_of(me.pid);
  return me;
}

Json ClaimHolder::to_json() const {
  return {{"host", host}, {"host_key", host_key}, {"pid", pid}, {"pid_start", pid_start}};
}

ClaimHolder ClaimHolder::from_json(const Json& j) {
  ClaimHolder h;
  if (j.is_object()) {
    h.host = j.value("host", std::string());
    h.host_key = j.value("host_key", std::string());
    h.pid = j.value("pid", int64_t{0});
    h.pid_start = j.value("pid_start", uint64_t{0});
  }
  return h;
}

std::string ClaimHolder::name() const { return (host.empty() ? "?" : host) + ":" + std::to_string(pid); }

bool process_alive(int64_t pid, uint64_t pid_start) {
  if (pid <= 0) return false;
  // EPERM: it exists but belongs to someone else.
  if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno != EPERM) return false;
  if (pid_start == 0) return true;
  const uint64_t now_start = start_ticks_of(pid);
  return now_start == 0 || now_start == pid_start;  // a different start time: the pid was reused
}

std::optional<std::string> stale_reason(const ClaimHolder& holder, const ClaimHolder& me, double heartbeat_age_s,
                                        double stale_after_s, const std::function<bool(int64_t, uint64_t)>& alive) {
  const bool same_host = !holder.host.empty() && holder.host == me.host && holder.host_key == me.host_key;
  if (same_host) {
    if (alive(holder.pid, holder.pid_start)) return std::nullopt;
    return "process " + std::to_string(holder.pid) + " on this host (" + holder.host + ") is gone";
  }
  if (heartbeat_age_s <= stale_after_s) return std::nullopt;
  char text[160];
  std::snprintf(text, sizeof text, "no heartbeat from %s for %.0f s (the limit is %.0f s)", holder.name().c_str(),
                heartbeat_age_s, stale_after_s);
  return std::string(text);
}

RunClaims::RunClaims(fs::path claims_dir, std::chrono::seconds stale_after)
    : dir_(std::move(claims_dir)), stale_after_(stale_after), me_(ClaimHolder::self()), serial_([] {
        static std::atomic<uint64_t> made{0};
        return made++;
      }()) {
  fs::create_directories(dir_);
  heartbeat_ = std::thread([this] { heartbeat_loop(); });
}

RunClaims::~RunClaims() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  heartbeat_.join();
  std::vector<std::string> held;
  for (const auto& [run_id, generation] : held_) held.push_back(run_id);
  for (const auto& run_id : held) release(run_id, false);
  std::error_code ec;
  fs::remove(dir_ / (".clock." + me_.host + "." + std::to_string(me_.pid)), ec);
  for (const auto& [worker, file] : holders_) fs::remove(file, ec);
}

fs::path RunClaims::holder_file(unsigned worker) {
  {
    std::lock_guard lock(mutex_);
    const auto it = holders_.find(worker);
    if (it != holders_.end()) return it->second;
  }
  const fs::path file = dir_ / (".holder." + me_.host + "." + std::to_string(me_.pid) + "." + std::to_string(serial_) +
                                "." + std::to_string(worker));
  // The record is complete before any claim's name links to it: nobody reads a half-written claim.
  std::error_code ec;
  fs::remove(file, ec);
  if (!create_file(file, me_.to_json().dump() + "\n"))
    throw std::runtime_error(file.string() + ": cannot write a claim file: " + std::strerror(errno));
  std::lock_guard lock(mutex_);
  holders_[worker] = file;
  return file;
}

fs::path RunClaims::claim_file(const std::string& run_id, uint64_t generation) const {
  return dir_ / (run_id + "." + std::to_string(generation));
}

bool RunClaims::try_link(const fs::path& file, const std::string& run_id, uint64_t generation, unsigned worker) {
  const fs::path holder = holder_file(worker);
  bool linked = ::link(holder.c_str(), file.c_str()) == 0;
  if (!linked && errno != EEXIST) {
    // NFS may report a failure for a link that was made (a lost reply): the
    // link count tells, the worker holding no other claim.
    struct stat st {};
    linked = ::stat(holder.c_str(), &st) == 0 && st.st_nlink == 2;
  }
  if (linked) {
    std::lock_guard lock(mutex_);
    held_[run_id] = generation;
  }
  return linked;
}

std::optional<double> RunClaims::heartbeat_age_s(const fs::path& file) {
  struct stat claim {};
  if (::stat(file.c_str(), &claim) != 0) return std::nullopt;
  // "Now" as the file system sees it: the modification time of a file we touch,
  // so that clock differences between hosts do not count as age.
  const fs::path clock = dir_ / (".clock." + me_.host + "." + std::to_string(me_.pid));
  const int fd = ::open(clock.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  struct stat now {};
  const bool ok = fd >= 0 && ::futimens(fd, nullptr) == 0 && ::fstat(fd, &now) == 0;
  if (fd >= 0) ::close(fd);
  if (!ok) throw std::runtime_error(clock.string() + ": cannot write: " + std::strerror(errno));
  return std::max(0.0, seconds_between(now.st_mtim, claim.st_mtim));
}

ClaimOutcome RunClaims::claim(const std::string& run_id, unsigned worker) {
  ClaimOutcome stale;  // the last stale claim passed over, reported when we take the next generation
  bool passed_stale = false;
  // A claim that vanishes under us was released by a finished run: look again from the start, a few times.
  for (int attempt = 0; attempt < 4; ++attempt) {
    for (uint64_t generation = 0;; ++generation) {
      const fs::path file = claim_file(run_id, generation);
      if (try_link(file, run_id, generation, worker)) {
        if (!passed_stale) return {ClaimOutcome::Kind::taken, {}, {}};
        stale.kind = ClaimOutcome::Kind::retaken;
        return stale;
      }
      if (fs::exists(claim_file(run_id, generation + 1))) continue;  // superseded by a later claim
      const auto record = read_record(file);
      const auto age = heartbeat_age_s(file);
      if (!record || !age) break;  // released meanwhile
      const ClaimHolder holder = ClaimHolder::from_json(*record);
      if (record->value("released", false)) {
        passed_stale = false;  // given back in order: no warning
        continue;
      }
      const auto reason = stale_reason(holder, me_, *age, static_cast<double>(stale_after_.count()));
      if (!reason) return {ClaimOutcome::Kind::busy, holder, {}};
      stale = {ClaimOutcome::Kind::retaken, holder, *reason};
      passed_stale = true;
    }
  }
  return {ClaimOutcome::Kind::busy, {}, "claims of this run changed repeatedly while being read"};
}

void RunClaims::release(const std::string& run_id, bool run_finished) {
  uint64_t generation;
  {
    std::lock_guard lock(mutex_);
    const auto it = held_.find(run_id);
    if (it == held_.end()) return;
    generation = it->second;
    held_.erase(it);
  }
  if (run_finished) {
    remove_leftovers(run_id);
    return;
  }
  // Replaced, never removed: a gap in the generations would let a newcomer
  // claim an old generation beside a live newer one.
  Json record = me_.to_json();
  record["run_id"] = run_id;
  record["released"] = true;
  const fs::path file = claim_file(run_id, generation);
  const fs::path temp = file.string() + "." + me_.host + "." + std::to_string(me_.pid) + ".released.tmp";
  std::error_code ec;
  if (create_file(temp, record.dump() + "\n")) fs::rename(temp, file, ec);
  if (ec) fs::remove(temp, ec);
}

std::optional<ClaimHolder> RunClaims::holder_of(const std::string& run_id) {
  uint64_t generation = 0;
  if (!fs::exists(claim_file(run_id, 0))) return std::nullopt;
  while (fs::exists(claim_file(run_id, generation + 1))) ++generation;
  const fs::path file = claim_file(run_id, generation);
  const auto record = read_record(file);
  const auto age = heartbeat_age_s(file);
  if (!record || !age || record->value("released", false)) return std::nullopt;
  const ClaimHolder holder = ClaimHolder::from_json(*record);
  if (stale_reason(holder, me_, *age, static_cast<double>(stale_after_.count()))) return std::nullopt;
  return holder;
}

void RunClaims::remove_leftovers(const std::string& run_id) {
  std::error_code ec;
  for (uint64_t generation = 0; fs::remove(claim_file(run_id, generation), ec); ++generation) {
  }
}

void RunClaims::heartbeat_loop() {
  const auto interval = std::clamp<std::chrono::milliseconds>(stale_after_ / 10, std::chrono::seconds(1),
                                                               std::chrono::seconds(60));
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, interval, [this] { return stopping_; })) {
    for (const auto& [run_id, generation] : held_)
      ::utimensat(AT_FDCWD, claim_file(run_id, generation).c_str(), nullptr, 0);
  }
}

}  // namespace latsim::sweep
