// Coroutine processes: delay, until, interleaving and failure propagation.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "latsim/des/process.hpp"

using latsim::des::Process;
using latsim::des::Simulator;
using latsim::des::Time;

namespace {

// Lines of "<ms>ms <what>" in the order processes wrote them.
struct Log {
  std::vector<std::string> lines;
  void add(const Simulator& sim, const std::string& what) {
    lines.push_back(std::to_string(sim.now().ticks() / 1'000'000'000) + "ms " + what);
  }
};

Process ticker(Simulator& sim, Log& log, std::string name, Time period, int count) {
  for (int i = 0; i < count; ++i) {
    co_await sim.delay(period);
    log.add(sim, name + std::to_string(i));
  }
}

Process sleeper(Simulator& sim, Log& log) {
  log.add(sim, "start");
  co_await sim.until(Time::ms(7));
  log.add(sim, "woke");
  co_await sim.delay(Time::zero());
  log.add(sim, "after zero delay");
}

Process failing(Simulator& sim) {
  co_await sim.delay(Time::ms(2));
  throw std::runtime_error("process failed at 2 ms");
}

Process waits_forever(Simulator& sim, int& resumed) {
  co_await sim.delay(Time::s(100));
  ++resumed;
}

}  // namespace

TEST_CASE("processes interleave by simulated time, FIFO on ties", "[process]") {
  Simulator sim;
  Log log;
  sim.spawn(ticker(sim, log, "a", Time::ms(2), 3));
  sim.spawn(ticker(sim, log, "b", Time::ms(3), 2));
  sim.run();
  // At 6 ms, b1's wake-up was scheduled (at 3 ms) before a2's (at 4 ms).
  const std::vector<std::string> expected{"2ms a0", "3ms b0", "4ms a1", "6ms b1", "6ms a2"};
  CHECK(log.lines == expected);
  CHECK(sim.now() == Time::ms(6));
  CHECK(sim.empty());
}

TEST_CASE("until waits for an absolute time, zero delay yields", "[process]") {
  Simulator sim;
  Log log;
  const auto k = sim.kind("test.plain");
  sim.spawn(sleeper(sim, log));
  // Scheduled after the process's wake-up for 7 ms, before its zero delay.
  sim.at(Time::ms(5), k, [&] { sim.at(Time::ms(7), k, [&] { log.add(sim, "plain event"); }); });
  sim.run();
  const std::vector<std::string> expected{"0ms start", "7ms woke", "7ms plain event", "7ms after zero delay"};
  CHECK(log.lines == expected);
  const auto stats = sim.kind_stats();
  REQUIRE(stats.size() == 2);
  CHECK(stats[1].name == "process");
  CHECK(stats[1].events == 3);
}

TEST_CASE("a spawned process can be given its own event kind", "[process]") {
  Simulator sim;
  Log log;
  const auto k = sim.kind("pxpl5.copy");
  sim.spawn(ticker(sim, log, "x", Time::ms(1), 4), k);
  sim.run();
  CHECK(sim.kind_stats().at(k).events == 5);  // start + four resumptions
}

TEST_CASE("exceptions thrown inside a process propagate out of run", "[process]") {
  Simulator sim;
  Log log;
  sim.spawn(failing(sim));
  sim.spawn(ticker(sim, log, "t", Time::ms(1), 5));
  CHECK_THROWS_WITH(sim.run(), "process failed at 2 ms");
  CHECK(sim.now() == Time::ms(2));
  sim.run();  // the other process carries on
  CHECK(log.lines.size() == 5);
}

TEST_CASE("negative delays and times in the past are rejected", "[process]") {
  Simulator sim;
  const auto k = sim.kind("test.advance");
  sim.at(Time::ms(5), k, [] {});
  sim.run();
  CHECK_THROWS_AS(sim.delay(Time::ps(-1)), std::logic_error);
  CHECK_THROWS_AS(sim.until(Time::ms(4)), std::logic_error);
}

TEST_CASE("unfinished processes are destroyed with the simulator", "[process]") {
  int resumed = 0;
  {
    Simulator sim;
    sim.spawn(waits_forever(sim, resumed));
    sim.run_until(Time::s(1));
    CHECK(sim.pending() == 1);
  }
  CHECK(resumed == 0);
  // Never spawned: the Process object owns and frees its frame.
  Simulator sim;
  { Process p = waits_forever(sim, resumed); }
  CHECK(sim.empty());
}
