// Event ordering, cancellation, run control, fingerprints and accounting.
#include <catch2/catch.hpp>

#include <array>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "latsim/des/simulator.hpp"

using latsim::des::EventId;
using latsim::des::QueueKind;
using latsim::des::Simulator;
using latsim::des::Time;

namespace {

const auto kQueueKinds = {QueueKind::quaternary_heap, QueueKind::binary_heap};

}  // namespace

TEST_CASE("events run in (time, priority, insertion) order", "[simulator]") {
  for (const QueueKind qk : kQueueKinds) {
    Simulator sim(qk);
    const auto k = sim.kind("test.order");
    std::vector<std::string> log;
    auto note = [&](std::string s) { return [&log, s] { log.push_back(s); }; };
    sim.at(Time::ms(2), k, note("t2 p0 first"));
    sim.at(Time::ms(1), k, note("t1 p5"), 5);
    sim.at(Time::ms(2), k, note("t2 p0 second"));
    sim.at(Time::ms(1), k, note("t1 p-3"), -3);
    sim.at(Time::ms(2), k, note("t2 p-1"), -1);
    sim.at(Time::ms(1), k, note("t1 p0"));
    sim.at(Time::ms(2), k, note("t2 p0 third"));
    sim.run();
    const std::vector<std::string> expected{"t1 p-3",       "t1 p0",        "t1 p5",      "t2 p-1",
                                            "t2 p0 first", "t2 p0 second", "t2 p0 third"};
    CHECK(log == expected);
    CHECK(sim.now() == Time::ms(2));
    CHECK(sim.events_executed() == 7);
    CHECK(sim.empty());
  }
}

TEST_CASE("events scheduled from callbacks at the same time run after those already due", "[simulator]") {
  for (const QueueKind qk : kQueueKinds) {
    Simulator sim(qk);
    const auto k = sim.kind("test.chain");
    std::vector<int> log;
    sim.at(Time::us(1), k, [&] {
      log.push_back(1);
      sim.after(Time::zero(), k, [&] { log.push_back(3); });
      sim.after(Time::zero(), k, [&] { log.push_back(4); }, -1);  // priority beats insertion
    });
    sim.at(Time::us(1), k, [&] { log.push_back(2); });
    sim.run();
    CHECK(log == std::vector<int>{1, 4, 2, 3});
  }
}

TEST_CASE("scheduling in the past or with a negative delay throws", "[simulator]") {
  Simulator sim;
  const auto k = sim.kind("test.misuse");
  sim.at(Time::ms(5), k, [] {});
  sim.run();
  CHECK_THROWS_AS(sim.at(Time::ms(4), k, [] {}), std::logic_error);
  CHECK_THROWS_AS(sim.after(Time::ps(-1), k, [] {}), std::logic_error);
  CHECK_THROWS_AS(sim.at(Time::ms(6), k + 100, [] {}), std::logic_error);
  CHECK_THROWS_AS(sim.run_until(Time::ms(1)), std::logic_error);
  CHECK_NOTHROW(sim.at(Time::ms(5), k, [] {}));
  CHECK(sim.pending() == 1);
}

TEST_CASE("cancelled events never run, cancelling twice or after running returns false", "[simulator]") {
  for (const QueueKind qk : kQueueKinds) {
    Simulator sim(qk);
    const auto k = sim.kind("test.cancel");
    std::vector<int> log;
    const EventId a = sim.at(Time::ms(1), k, [&] { log.push_back(1); });
    const EventId b = sim.at(Time::ms(2), k, [&] { log.push_back(2); });
    const EventId c = sim.at(Time::ms(3), k, [&] { log.push_back(3); });
    sim.at(Time::ms(1), k, [&] { CHECK(sim.cancel(c)); }, 1);
    CHECK(a.valid());
    CHECK_FALSE(EventId{}.valid());
    CHECK(sim.pending() == 4);
    CHECK(sim.cancel(b));
    CHECK(sim.pending() == 3);
    CHECK_FALSE(sim.cancel(b));  // already cancelled
    CHECK_FALSE(sim.cancel(EventId{}));
    CHECK_FALSE(sim.cancel(EventId{0xffff'ffff'0000'0000ull | 12345}));
    sim.run();
    CHECK(log == std::vector<int>{1});
    CHECK_FALSE(sim.cancel(a));  // already ran
    CHECK_FALSE(sim.cancel(c));  // cancelled from a callback
    CHECK(sim.events_executed() == 2);
    CHECK(sim.empty());

    // A freed slot is reused, but the old id must not cancel the new event.
    const EventId d = sim.after(Time::ms(1), k, [&] { log.push_back(4); });
    CHECK_FALSE(sim.cancel(a));
    CHECK(d != a);
    sim.run();
    CHECK(log == std::vector<int>{1, 4});
  }
}

TEST_CASE("an event cannot cancel itself while running", "[simulator]") {
  Simulator sim;
  const auto k = sim.kind("test.self");
  EventId self;
  bool result = true;
  self = sim.at(Time::ms(1), k, [&] { result = sim.cancel(self); });
  sim.run();
  CHECK_FALSE(result);
}

TEST_CASE("run_until runs events up to and including the end time, then sets now", "[simulator]") {
  for (const QueueKind qk : kQueueKinds) {
    Simulator sim(qk);
    const auto k = sim.kind("test.until");
    std::vector<int> log;
    for (int i = 1; i <= 5; ++i) sim.at(Time::ms(i), k, [&log, i] { log.push_back(i); });
    sim.run_until(Time::ms(3));
    CHECK(log == std::vector<int>{1, 2, 3});
    CHECK(sim.now() == Time::ms(3));
    CHECK(sim.pending() == 2);
    sim.run_until(Time::us(3500));
    CHECK(sim.now() == Time::us(3500));
    CHECK(log.size() == 3);
    sim.run_until(Time::s(1));
    CHECK(log == std::vector<int>{1, 2, 3, 4, 5});
    CHECK(sim.now() == Time::s(1));
  }
}

TEST_CASE("stop ends the run after the current event, run resumes", "[simulator]") {
  Simulator sim;
  const auto k = sim.kind("test.stop");
  std::vector<int> log;
  for (int i = 1; i <= 4; ++i) {
    sim.at(Time::ms(i), k, [&, i] {
      log.push_back(i);
      if (i == 2) sim.stop();
    });
  }
  sim.run();
  CHECK(log == std::vector<int>{1, 2});
  CHECK(sim.now() == Time::ms(2));
  sim.at(Time::ms(3), k, [&] { sim.stop(); }, -1);
  sim.run_until(Time::ms(10));
  CHECK(log == std::vector<int>{1, 2});
  CHECK(sim.now() == Time::ms(3));  // stopped: now stays at the stopping event
  sim.run();
  CHECK(log == std::vector<int>{1, 2, 3, 4});
}

TEST_CASE("an exception from a callback propagates and leaves the simulator usable", "[simulator]") {
  Simulator sim;
  const auto k = sim.kind("test.throw");
  int ran = 0;
  sim.at(Time::ms(1), k, [] { throw std::runtime_error("model failure"); });
  sim.at(Time::ms(2), k, [&] { ++ran; });
  CHECK_THROWS_WITH(sim.run(), "model failure");
  CHECK(sim.pending() == 1);
  sim.run();
  CHECK(ran == 1);
}

namespace {

// A small self-scheduling model whose event times depend on `shift`.
uint64_t chain_fingerprint(QueueKind qk, Time shift) {
  Simulator sim(qk);
  const auto tick = sim.kind("model.tick");
  const auto tock = sim.kind("model.tock");
  int count = 0;
  std::function<void()> step = [&] {
    if (++count > 50) return;
    sim.after(Time::us(100 + count % 7), count % 2 ? tick : tock, step);
  };
  sim.at(Time::zero(), tick, step);
  sim.at(Time::us(250) + shift, tock, [] {});
  sim.run();
  return sim.fingerprint();
}

}  // namespace

TEST_CASE("fingerprint is reproducible and sensitive to event times", "[simulator]") {
  const uint64_t a = chain_fingerprint(QueueKind::quaternary_heap, Time::zero());
  CHECK(a == chain_fingerprint(QueueKind::quaternary_heap, Time::zero()));
  CHECK(a == chain_fingerprint(QueueKind::binary_heap, Time::zero()));
  CHECK(a != chain_fingerprint(QueueKind::quaternary_heap, Time::ps(1)));
  CHECK(Simulator().fingerprint() == 0);
  // Pinned: the hash is defined over kind names and ticks, not over memory
  // addresses or std::hash, so it must not change between runs or platforms.
  CHECK(a == 0x01814d414f36f61eull);
}

TEST_CASE("kind and model statistics count events", "[simulator]") {
  Simulator sim;
  const auto a = sim.kind("tracker.sample");
  const auto b = sim.kind("display.vsync");
  const auto c = sim.kind("tracker.transport");
  CHECK(sim.kind("display.vsync") == b);
  CHECK(sim.kind_name(c) == "tracker.transport");
  for (int i = 0; i < 3; ++i) sim.at(Time::ms(i), a, [] {});
  sim.at(Time::ms(1), b, [] {});
  sim.at(Time::ms(1), c, [] {});
  sim.set_profiling(true);
  sim.run();
  const auto kinds = sim.kind_stats();
  REQUIRE(kinds.size() == 3);
  CHECK(kinds[0].name == "tracker.sample");
  CHECK(kinds[0].events == 3);
  CHECK(kinds[1].events == 1);
  CHECK(kinds[2].events == 1);
  CHECK(kinds[0].wall_s >= 0.0);
  const auto models = sim.model_stats();
  REQUIRE(models.size() == 2);
  CHECK(models[0].model == "display");
  CHECK(models[0].events == 1);
  CHECK(models[1].model == "tracker");
  CHECK(models[1].events == 4);
}

TEST_CASE("large captures fall back to the heap and still run", "[simulator]") {
  Simulator sim;
  const auto k = sim.kind("test.large");
  std::array<int, 64> payload{};
  payload[63] = 42;
  int seen = 0;
  sim.at(Time::ms(1), k, [payload, &seen] { seen = payload[63]; });
  sim.run();
  CHECK(seen == 42);
}

namespace {

// What the slab-growth tests' callbacks share: a few bytes of capture, so
// that the callbacks themselves lie inline in the slab.
struct GrowthContext {
  Simulator& sim;
  latsim::des::KindId kind;
  int burst;
  std::vector<std::string> ran;
};

using InlineCallback = latsim::des::InlineFunction<void(), 32>;

}  // namespace

// A callback runs in its slab slot. When it schedules so many events that the
// slab is reallocated (once or several times) while it runs, its captures
// must stay where they are until it returns, and every callback must still
// run exactly once with its captures intact. The captures are shared_ptrs:
// moved away, the running callback would see null; freed, ASan reports a
// use-after-free.
TEST_CASE("a callback that makes the slab grow keeps its captures until it returns", "[simulator]") {
  for (const QueueKind qk : kQueueKinds) {
    for (const int burst : {10, 100, 1000}) {  // no growth, one, several
      std::weak_ptr<std::string> watch;
      {
        Simulator sim(qk);
        GrowthContext ctx{sim, sim.kind("test.grow"), burst, {}};
        auto text = std::make_shared<std::string>(40, 'a');
        watch = text;
        auto parent = [c = &ctx, text = std::move(text)] {
          for (int i = 0; i < c->burst; ++i) {
            auto child = [c, tag = std::make_shared<std::string>("child " + std::to_string(i))] {
              c->ran.push_back(*tag);
            };
            static_assert(InlineCallback::stores_inline<decltype(child)>);
            c->sim.at(Time::ms(2), c->kind, std::move(child));
            REQUIRE(text != nullptr);  // read after every schedule, growth included
            REQUIRE(*text == std::string(40, 'a'));
          }
          c->ran.push_back(*text);
        };
        static_assert(InlineCallback::stores_inline<decltype(parent)>);
        sim.at(Time::ms(1), ctx.kind, std::move(parent));
        sim.run();
        REQUIRE(ctx.ran.size() == static_cast<std::size_t>(burst) + 1);
        CHECK(ctx.ran.front() == std::string(40, 'a'));
        for (int i = 0; i < burst; ++i) CHECK(ctx.ran[static_cast<std::size_t>(i) + 1] == "child " + std::to_string(i));
        CHECK(watch.expired());  // the parent's capture was destroyed when it returned
      }
    }
  }
}

TEST_CASE("a callback that makes the slab grow and then throws leaves the simulator usable", "[simulator]") {
  Simulator sim;
  GrowthContext ctx{sim, sim.kind("test.grow_throw"), 500, {}};
  auto text = std::make_shared<std::string>("kept");
  const std::weak_ptr<std::string> watch = text;
  EventId last_child;
  auto parent = [c = &ctx, text = std::move(text), &last_child] {
    for (int i = 0; i < c->burst; ++i) last_child = c->sim.at(Time::ms(2), c->kind, [c] { c->ran.emplace_back(); });
    throw std::runtime_error("failed after " + *text);
  };
  static_assert(InlineCallback::stores_inline<decltype(parent)>);
  sim.at(Time::ms(1), ctx.kind, std::move(parent));
  CHECK_THROWS_WITH(sim.run(), "failed after kept");
  CHECK(watch.expired());  // the callback that threw is destroyed
  CHECK(sim.pending() == 500);
  CHECK(sim.cancel(last_child));
  sim.run();
  CHECK(ctx.ran.size() == 499);
}
