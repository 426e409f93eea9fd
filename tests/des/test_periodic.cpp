// Periodic activities, processes started within an event, and handoffs.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "latsim/des/handoff.hpp"
#include "latsim/des/periodic.hpp"
#include "latsim/des/process.hpp"

using namespace latsim::des;

TEST_CASE("a periodic activity runs at times computed from the index, exactly, for hours at 59.94 Hz", "[periodic]") {
  Simulator sim;
  // 59.94 Hz: the period is 1001/60000 s.
  const PeriodicSchedule schedule(Time::zero(), RationalSeconds{1001, 60000});
  int64_t mismatches = 0, last = -1;
  Periodic ticks(sim, schedule, sim.kind("test.tick"), [&](int64_t k) {
    // Second method: t_k = floor(k * 1001 * 10^12 / 60000) ps in 128-bit integers.
    const __int128 expect = static_cast<__int128>(k) * 1001 * 1'000'000'000'000LL / 60000;
    if (sim.now().ticks() != static_cast<int64_t>(expect) || k != last + 1) ++mismatches;
    last = k;
  });
  const Time end = Time::s(3 * 3600);
  ticks.start(0, end);
  sim.run_until(end);
  CHECK(mismatches == 0);
  // Occurrences before 3 h: k * 1001 / 60000 < 10800, so k <= 647352 (10800 * 60000 / 1001 = 647352.6...).
  CHECK(last == 647352);
  CHECK(ticks.count() == 647353);
  CHECK(sim.events_executed() == 647353);
}

TEST_CASE("each occurrence schedules the next before its function runs", "[periodic]") {
  Simulator sim;
  std::vector<std::string> log;
  const KindId other = sim.kind("test.other");
  Periodic ticks(sim, PeriodicSchedule(Time::ms(5), RationalSeconds{1, 100}), sim.kind("test.tick"), [&](int64_t k) {
    log.push_back("tick" + std::to_string(k));
    // Something at the instant of the next tick comes after that tick.
    sim.at(sim.now() + Time::ms(10), other, [&log, k] { log.push_back("after" + std::to_string(k)); });
  });
  ticks.start(0, Time::ms(30));
  sim.run();
  // Ticks at 5, 15 and 25 ms; nothing at or after 30 ms.
  CHECK(log == std::vector<std::string>{"tick0", "tick1", "after0", "tick2", "after1", "after2"});
  CHECK(sim.now() == Time::ms(35));
}

TEST_CASE("a periodic activity starts at any index and stops", "[periodic]") {
  Simulator sim;
  std::vector<int64_t> seen;
  Periodic ticks(sim, PeriodicSchedule(Time::zero(), RationalSeconds{1, 10}), sim.kind("test.tick"),
                 [&](int64_t k) { seen.push_back(k); });
  sim.run_until(Time::ms(250));
  ticks.start(ticks.schedule().index_at_or_after(sim.now()), Time::s(10));
  sim.run_until(Time::ms(500));
  ticks.stop();
  sim.run_until(Time::s(2));
  CHECK(seen == std::vector<int64_t>{3, 4, 5});
  CHECK(sim.empty());
}

namespace {

Process two_steps(Simulator& sim, std::vector<std::string>& log) {
  log.push_back("started at " + std::to_string(sim.now().ticks()));
  co_await sim.delay(Time::ps(7));
  log.push_back("resumed at " + std::to_string(sim.now().ticks()));
}

Process parked(Handoff& h, Simulator& sim, std::vector<std::string>& log) {
  for (int i = 0; i < 2; ++i) {
    co_await h;
    log.push_back("continued at " + std::to_string(sim.now().ticks()));
  }
}

}  // namespace

TEST_CASE("a process started within an event costs no event of its own", "[process]") {
  Simulator sim;
  std::vector<std::string> log;
  const KindId kind = sim.kind("test.proc");
  sim.at(Time::ps(3), kind, [&] { sim.start(two_steps(sim, log), kind); });
  sim.run();
  CHECK(log == std::vector<std::string>{"started at 3", "resumed at 10"});
  // The scheduling event and the one resumption: the start itself is not an event.
  CHECK(sim.events_executed() == 2);
  for (const auto& k : sim.kind_stats())
    if (k.name == "test.proc") CHECK(k.events == 2);
}

TEST_CASE("a handoff continues its process inside the event that resumes it", "[process]") {
  Simulator sim;
  std::vector<std::string> log;
  Handoff h;
  sim.start(parked(h, sim, log), sim.kind("test.proc"));
  CHECK(h.waiting());
  CHECK(log.empty());
  const KindId kind = sim.kind("test.event");
  sim.at(Time::ps(5), kind, [&] {
    log.push_back("event");
    CHECK(h.resume());
    log.push_back("event goes on");
  });
  sim.run();
  CHECK(log == std::vector<std::string>{"event", "continued at 5", "event goes on"});
  CHECK(sim.events_executed() == 1);
  CHECK(h.waiting());
  CHECK(h.resume());   // the second continuation ends the process
  CHECK_FALSE(h.waiting());
  CHECK_FALSE(h.resume());
}
