// Signals (single, all_of, any_of) and FIFO resources with busy time.
#include <catch2/catch.hpp>

#include <memory>
#include <string>
#include <vector>

#include "latsim/des/resource.hpp"
#include "latsim/des/signal.hpp"

using latsim::des::all_of;
using latsim::des::any_of;
using latsim::des::Process;
using latsim::des::Resource;
using latsim::des::Signal;
using latsim::des::Simulator;
using latsim::des::Time;

namespace {

using Log = std::vector<std::pair<std::string, Time>>;

Process wait_one(Simulator& sim, Signal& s, Log& log, std::string name) {
  co_await s;
  log.emplace_back(name, sim.now());
}

Process wait_all(Simulator& sim, Signal& a, Signal& b, Log& log) {
  co_await all_of(a, b);
  log.emplace_back("all", sim.now());
}

Process wait_any(Simulator& sim, std::vector<Signal*> signals, Log& log) {
  co_await any_of(std::move(signals));
  log.emplace_back("any", sim.now());
}

Process fire(Simulator& sim, Signal& s, Time at) {
  co_await sim.until(at);
  s.trigger();
}

Process job(Simulator& sim, Resource& r, Log& log, std::string name, Time start, Time hold) {
  co_await sim.until(start);
  co_await r.acquire();
  log.emplace_back(name + " got", sim.now());
  co_await sim.delay(hold);
  r.release();
}

}  // namespace

TEST_CASE("signal waiters resume FIFO at the trigger time", "[signal]") {
  Simulator sim;
  Signal s(sim, "frame_done");
  Log log;
  sim.spawn(wait_one(sim, s, log, "first"));
  sim.spawn(wait_one(sim, s, log, "second"));
  sim.spawn(fire(sim, s, Time::ms(4)));
  sim.run();
  REQUIRE(log.size() == 2);
  CHECK(log[0] == std::make_pair(std::string("first"), Time::ms(4)));
  CHECK(log[1] == std::make_pair(std::string("second"), Time::ms(4)));
  CHECK(s.triggered());
  CHECK(s.waiter_count() == 0);

  // Already triggered: continue at once.
  sim.spawn(wait_one(sim, s, log, "late"));
  sim.run();
  CHECK(log.back() == std::make_pair(std::string("late"), Time::ms(4)));

  CHECK_THROWS_AS(s.trigger(), std::logic_error);
  s.reset();
  CHECK_FALSE(s.triggered());
  sim.spawn(wait_one(sim, s, log, "after reset"));
  sim.spawn(fire(sim, s, Time::ms(9)));
  sim.run();
  CHECK(log.back() == std::make_pair(std::string("after reset"), Time::ms(9)));
}

TEST_CASE("all_of waits for every signal, any_of for the first", "[signal]") {
  Simulator sim;
  Signal left(sim, "left"), right(sim, "right"), other(sim, "other");
  Log log;
  sim.spawn(wait_all(sim, left, right, log));
  sim.spawn(wait_any(sim, {&left, &right, &other}, log));
  sim.spawn(fire(sim, right, Time::ms(3)));
  sim.spawn(fire(sim, left, Time::ms(5)));
  sim.run();
  REQUIRE(log.size() == 2);
  CHECK(log[0] == std::make_pair(std::string("any"), Time::ms(3)));
  CHECK(log[1] == std::make_pair(std::string("all"), Time::ms(5)));
  // any_of unregistered itself from the signals that did not fire.
  CHECK(other.waiter_count() == 0);
  CHECK(left.waiter_count() == 0);

  // Ready at once when already satisfied.
  sim.spawn(wait_all(sim, left, right, log));
  sim.run();
  CHECK(log.back() == std::make_pair(std::string("all"), Time::ms(5)));
}

TEST_CASE("waiters on signals are cleaned up when the simulator ends early", "[signal]") {
  Simulator sim;
  Signal never(sim, "never");
  Log log;
  sim.spawn(wait_one(sim, never, log, "x"));
  sim.spawn(wait_all(sim, never, never, log));
  sim.run();
  CHECK(never.waiter_count() == 3);  // all_of(never, never) waits on it twice
  CHECK(log.empty());
}

TEST_CASE("a fired signal may be destroyed while an all_of wait on it is still pending", "[signal]") {
  // The waiter must forget a signal once it has fired: destroying that signal
  // and then the simulator (which tears the waiting process down) must not
  // touch freed memory (AddressSanitizer checks this).
  auto sim = std::make_unique<Simulator>();
  auto a = std::make_unique<Signal>(*sim, "a");
  Signal b(*sim, "b");
  Log log;
  sim->spawn(wait_all(*sim, *a, b, log));
  sim->spawn(fire(*sim, *a, Time::ms(1)));
  sim->run();
  CHECK(log.empty());
  CHECK(b.waiter_count() == 1);
  a.reset();
  sim.reset();
  CHECK(b.waiter_count() == 0);
}

TEST_CASE("resource with capacity 1 queues FIFO and measures busy time", "[resource]") {
  Simulator sim;
  Resource ring(sim, 1, "ring");
  Log log;
  sim.spawn(job(sim, ring, log, "a", Time::ms(0), Time::ms(3)));
  sim.spawn(job(sim, ring, log, "b", Time::ms(1), Time::ms(2)));
  sim.spawn(job(sim, ring, log, "c", Time::ms(2), Time::ms(1)));
  sim.spawn(job(sim, ring, log, "d", Time::ms(10), Time::ms(1)));
  sim.run_until(Time::ms(2));
  CHECK(ring.in_use() == 1);
  CHECK(ring.queue_length() == 2);
  sim.run();
  const Log expected{{"a got", Time::ms(0)}, {"b got", Time::ms(3)}, {"c got", Time::ms(5)}, {"d got", Time::ms(10)}};
  CHECK(log == expected);
  CHECK(ring.in_use() == 0);
  CHECK(ring.busy_time() == Time::ms(7));
  CHECK(ring.unit_busy_time() == Time::ms(7));
  CHECK_THROWS_AS(ring.release(), std::logic_error);
}

TEST_CASE("resource with capacity 2 serves two at once, then FIFO", "[resource]") {
  Simulator sim;
  Resource pair(sim, 2, "renderers");
  Log log;
  sim.spawn(job(sim, pair, log, "a", Time::ms(0), Time::ms(4)));
  sim.spawn(job(sim, pair, log, "b", Time::ms(1), Time::ms(4)));
  sim.spawn(job(sim, pair, log, "c", Time::ms(2), Time::ms(1)));
  sim.spawn(job(sim, pair, log, "d", Time::ms(2), Time::ms(1)));
  sim.run();
  const Log expected{{"a got", Time::ms(0)}, {"b got", Time::ms(1)}, {"c got", Time::ms(4)}, {"d got", Time::ms(5)}};
  CHECK(log == expected);
  // In use: 1 unit 0-1, 2 units 1-5, 1 unit 5-6 -> 10 unit-ms; busy 0-6.
  CHECK(pair.busy_time() == Time::ms(6));
  CHECK(pair.unit_busy_time() == Time::ms(10));
  CHECK_FALSE(pair.try_acquire() == false);
  CHECK(pair.in_use() == 1);
  CHECK_THROWS_AS(Resource(sim, 0), std::invalid_argument);
}
