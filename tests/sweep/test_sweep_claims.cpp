// Tests for per-run claims: one holder at a time, even when many race for a
// run or for a stale claim; stale claims from dead processes on this host and
// from silent hosts are retaken; released and finished claims behave.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "scratch_dir.hpp"
#include "latsim/sweep/claims.hpp"
#include "latsim/sweep/journal.hpp"

using latsim::sweep::ClaimHolder;
using latsim::sweep::ClaimOutcome;
using latsim::sweep::RunClaims;
using latsim::sweep::stale_reason;
using latsim::test::scratch_dir;
namespace fs = std::filesystem;
using Kind = ClaimOutcome::Kind;

namespace {

// The pid of a process that has exited and been reaped.
int64_t dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

// A holder on this host whose process is gone.
ClaimHolder dead_holder() {
  ClaimHolder ghost = ClaimHolder::self();
  ghost.pid = dead_pid();
  ghost.pid_start = 0;
  return ghost;
}

// A claim file as another process would have left it.
void write_claim(const fs::path& file, const ClaimHolder& holder) {
  auto record = holder.to_json();
  record["run_id"] = "r";
  std::ofstream(file) << record.dump() << "\n";
}

constexpr std::chrono::seconds kTenMinutes{600};

}  // namespace

TEST_CASE("a claim on this host is stale exactly when its process is gone", "[sweep][claims]") {
  const ClaimHolder me = ClaimHolder::self();
  ClaimHolder other = me;
  other.pid = 4242;
  auto alive = [](int64_t, uint64_t) { return true; };
  auto dead = [](int64_t, uint64_t) { return false; };
  // Age does not matter on the same host: only the process does.
  CHECK_FALSE(stale_reason(other, me, 1e6, 600, alive));
  const auto reason = stale_reason(other, me, 0, 600, dead);
  REQUIRE(reason);
  CHECK_THAT(*reason, Catch::Contains("process 4242 on this host") && Catch::Contains("is gone"));
}

TEST_CASE("a claim from another host is stale when its heartbeat is older than the limit", "[sweep][claims]") {
  const ClaimHolder me = ClaimHolder::self();
  ClaimHolder remote = me;
  remote.host = "node17";
  auto dead = [](int64_t, uint64_t) { return false; };  // must not be asked: the pid is another host's
  CHECK_FALSE(stale_reason(remote, me, 599, 600, dead));
  CHECK_FALSE(stale_reason(remote, me, 600, 600, dead));
  const auto reason = stale_reason(remote, me, 601, 600, dead);
  REQUIRE(reason);
  CHECK_THAT(*reason, Catch::Contains("no heartbeat from node17:") && Catch::Contains("for 601 s (the limit is 600 s)"));
  // Same host name, another kernel or pid namespace: its pids are not ours to check.
  ClaimHolder twin = me;
  twin.host_key = "another-boot/pid:[1]";
  CHECK_FALSE(stale_reason(twin, me, 10, 600, dead));
}

TEST_CASE("process_alive: this process, a reused pid, a dead one", "[sweep][claims]") {
  const ClaimHolder me = ClaimHolder::self();
  CHECK(latsim::sweep::process_alive(me.pid, me.pid_start));
  CHECK(latsim::sweep::process_alive(me.pid, 0));
  if (me.pid_start != 0) CHECK_FALSE(latsim::sweep::process_alive(me.pid, me.pid_start + 1));
  CHECK_FALSE(latsim::sweep::process_alive(dead_pid(), 0));
  CHECK_FALSE(latsim::sweep::process_alive(0, 0));
}

TEST_CASE("one holder per run: held, released, taken again, finished", "[sweep][claims]") {
  const fs::path dir = scratch_dir("latsim_claims_basic");
  {
    RunClaims a(dir, kTenMinutes);
    RunClaims b(dir, kTenMinutes);  // another worker of this same, live process
    CHECK(a.claim("r1").kind == Kind::taken);
    const auto busy = b.claim("r1");
    CHECK(busy.kind == Kind::busy);
    CHECK(busy.other.pid == ClaimHolder::self().pid);
    REQUIRE(b.holder_of("r1"));
    CHECK(b.holder_of("r1")->pid == ClaimHolder::self().pid);
    // Released without finishing: taken again at the next generation, with no warning.
    a.release("r1", false);
    CHECK_FALSE(b.holder_of("r1"));
    CHECK(b.claim("r1").kind == Kind::taken);
    CHECK(fs::exists(dir / "r1.1"));
    // Finished: every generation goes.
    b.release("r1", true);
    CHECK_FALSE(fs::exists(dir / "r1.0"));
    CHECK_FALSE(fs::exists(dir / "r1.1"));
    CHECK(a.claim("r2").kind == Kind::taken);
  }
  // Destroying the claims released what they held.
  RunClaims c(dir, kTenMinutes);
  CHECK(c.claim("r2").kind == Kind::taken);
  // A claim is a name of its worker's holder file, which says who holds it
  // (r2.0 is the record that a, destroyed, released r2).
  CHECK(fs::hard_link_count(dir / "r2.1") == 2);
  c.release("r2", true);
  // Only the live process's own files remain (its clock, its workers' holder files).
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    CHECK((name.rfind(".clock.", 0) == 0 || name.rfind(".holder.", 0) == 0));
  }
  fs::remove_all(dir);
}

TEST_CASE("a claim of a dead process on this host is retaken with its reason", "[sweep][claims]") {
  const fs::path dir = scratch_dir("latsim_claims_dead");
  const ClaimHolder ghost = dead_holder();
  write_claim(dir / "r.0", ghost);
  RunClaims claims(dir, kTenMinutes);
  const auto outcome = claims.claim("r");
  CHECK(outcome.kind == Kind::retaken);
  CHECK(outcome.other.pid == ghost.pid);
  CHECK_THAT(outcome.reason, Catch::Contains("is gone"));
  CHECK(fs::exists(dir / "r.1"));
  fs::remove_all(dir);
}

TEST_CASE("a claim from a silent host is retaken, a recent one respected", "[sweep][claims]") {
  const fs::path dir = scratch_dir("latsim_claims_remote");
  ClaimHolder remote = ClaimHolder::self();
  remote.host = "node17";
  remote.pid = 1;
  write_claim(dir / "fresh.0", remote);
  write_claim(dir / "silent.0", remote);
  // Its last heartbeat two hours ago, by the file's own clock.
  fs::last_write_time(dir / "silent.0", fs::last_write_time(dir / "silent.0") - std::chrono::hours(2));
  RunClaims claims(dir, kTenMinutes);
  CHECK(claims.claim("fresh").kind == Kind::busy);
  const auto outcome = claims.claim("silent");
  CHECK(outcome.kind == Kind::retaken);
  CHECK(outcome.other.host == "node17");
  CHECK_THAT(outcome.reason, Catch::Contains("no heartbeat from node17:1"));
  // A damaged claim file is judged by its heartbeat too.
  std::ofstream(dir / "damaged.0") << "{\"host\": ";
  CHECK(claims.claim("damaged").kind == Kind::busy);
  fs::remove_all(dir);
}

TEST_CASE("of many racing for a run, or for its stale claim, exactly one wins", "[sweep][claims]") {
  const fs::path dir = scratch_dir("latsim_claims_race");
  write_claim(dir / "stale.0", dead_holder());
  constexpr int kRacers = 8;
  for (const std::string run : {"fresh", "stale"}) {
    std::vector<std::unique_ptr<RunClaims>> racers;
    for (int i = 0; i < kRacers; ++i) racers.push_back(std::make_unique<RunClaims>(dir, kTenMinutes));
    std::atomic<int> ready{0}, winners{0}, busy{0};
    std::vector<std::thread> threads;
    for (int i = 0; i < kRacers; ++i)
      threads.emplace_back([&, i] {
        ++ready;
        while (ready < kRacers) std::this_thread::yield();  // start together
        const auto outcome = racers[static_cast<size_t>(i)]->claim(run);
        (outcome.kind == Kind::busy ? busy : winners)++;
      });
    for (auto& t : threads) t.join();
    CHECK(winners == 1);
    CHECK(busy == kRacers - 1);
  }
  fs::remove_all(dir);
}

TEST_CASE("the heartbeat refreshes every claim held", "[sweep][claims]") {
  const fs::path dir = scratch_dir("latsim_claims_heartbeat");
  RunClaims claims(dir, std::chrono::seconds(1));  // a heartbeat every second
  REQUIRE(claims.claim("r").kind == Kind::taken);
  const auto old = fs::last_write_time(dir / "r.0") - std::chrono::hours(1);
  fs::last_write_time(dir / "r.0", old);
  // Wait for it, however loaded the machine: no timing is asserted, only that it happens.
  for (int i = 0; i < 1200 && fs::last_write_time(dir / "r.0") == old; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  CHECK(fs::last_write_time(dir / "r.0") > old);
  fs::remove_all(dir);
}

TEST_CASE("the journal appends one line per event to its process's own file", "[sweep][claims]") {
  const fs::path dir = scratch_dir("latsim_journal");
  {
    latsim::sweep::SweepJournal journal(dir, "hostA", 42);
    journal.record("start", "r1");
    journal.record("fail", "r1", "bad\nthing");
  }
  latsim::sweep::SweepJournal again(dir, "hostA", 42);
  again.record("start", "r1");
  std::ifstream in(dir / "journal" / "hostA.42.log");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line.substr(line.find(' ') + 1));
  CHECK(lines == std::vector<std::string>{"start r1", "fail r1 bad thing", "start r1"});
  fs::remove_all(dir);
}
