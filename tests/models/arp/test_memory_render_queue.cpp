// Renderers as a resource: order, overlap, skipping, presentation order and
// utilisation, each against a hand-worked timeline written in the test.
#include <catch2/catch.hpp>

#include <utility>
#include <vector>

#include "latsim/arp/memory_render_queue.hpp"

using namespace latsim;
using des::Time;

namespace {

/// A queue with every event it reports written down.
struct Recorded {
  explicit Recorded(int renderers, int memories = 4)
      : queue(sim, sim.kind("arp.render"), renderers, memories,
              arp::MemoryRenderQueue::Listener{
                  .started = [this](int m, int64_t id) { starts.push_back({sim.now(), m, id}); ++in_progress; },
                  .finished = [this](int, int64_t) { --in_progress; },
                  .presented =
                      [this](const std::vector<std::pair<int, int64_t>>& batch) {
                        presents.push_back({sim.now(), batch});
                      },
                  .skipped = [this](int m, int64_t id) { skips.push_back({m, id}); }}) {}

  struct Start {
    Time at;
    int memory;
    int64_t id;
  };
  struct Present {
    Time at;
    std::vector<std::pair<int, int64_t>> batch;
  };

  des::Simulator sim;
  std::vector<Start> starts;
  std::vector<Present> presents;
  std::vector<std::pair<int, int64_t>> skips;
  int in_progress = 0;
  arp::MemoryRenderQueue queue;
};

arp::MemoryRenderQueue::Update update(int memory, int64_t cost_ms, std::vector<int> after = {}) {
  return {memory, Time::ms(cost_ms), std::move(after)};
}

}  // namespace

TEST_CASE("one renderer draws the fastest memory first and never two at once") {
  Recorded r(1);
  // Requested together: 3 (4 ms), 1 (2 ms), 0 (1 ms). Served 0, 1, 3 back to back:
  // 0 at 0-1 ms, 1 at 1-3 ms, 3 at 3-7 ms.
  r.queue.request({update(3, 4), update(1, 2), update(0, 1)});
  r.sim.run();
  REQUIRE(r.starts.size() == 3);
  CHECK(r.starts[0].memory == 0);
  CHECK(r.starts[0].at == Time::ms(0));
  CHECK(r.starts[1].memory == 1);
  CHECK(r.starts[1].at == Time::ms(1));
  CHECK(r.starts[2].memory == 3);
  CHECK(r.starts[2].at == Time::ms(3));
  // Each is presented when it finishes (nothing ties them).
  REQUIRE(r.presents.size() == 3);
  CHECK(r.presents[0].at == Time::ms(1));
  CHECK(r.presents[1].at == Time::ms(3));
  CHECK(r.presents[2].at == Time::ms(7));
  // Waits 0, 1 and 3 ms: mean 4/3 ms.
  CHECK(r.queue.queue_ms().stats().mean() == Approx(4.0 / 3.0));
  CHECK(r.queue.queue_ms().stats().max() == Approx(3.0));
  // Busy 7 ms of 10: utilisation 0.7.
  CHECK(r.queue.utilisation(Time::ms(10)) == Approx(0.7));
}

TEST_CASE("renders never overlap beyond the number of renderers") {
  for (int renderers : {1, 2, 3}) {
    Recorded r(renderers);
    int worst = 0;
    // Every millisecond, all four memories ask for 3 ms renders: far more than fits.
    for (int k = 0; k < 50; ++k) {
      r.sim.at(Time::ms(k), r.sim.kind("test.tick"), [&r] {
        r.queue.request({update(0, 3), update(1, 3), update(2, 3), update(3, 3)});
      });
      r.sim.at(Time::ms(k), r.sim.kind("test.check"), [&] { worst = std::max(worst, r.in_progress); }, 1);
    }
    r.sim.run();
    CHECK(worst == renderers);
    CHECK(!r.skips.empty());
  }
}

TEST_CASE("a newer request replaces a waiting one, which is skipped and keeps its place") {
  Recorded r(1);
  // t=0: memory 0 (10 ms) starts at once, memory 2 (1 ms) waits.
  // t=4: memory 2 again (2 ms): the waiting one is skipped, the new one waits in its place.
  // t=6: memory 1 (1 ms) asks; at t=10 the renderer takes memory 1 first (faster memory).
  r.queue.request({update(0, 10), update(2, 1)});
  r.sim.at(Time::ms(4), r.sim.kind("test.tick"), [&r] { r.queue.request({update(2, 2)}); });
  r.sim.at(Time::ms(6), r.sim.kind("test.tick"), [&r] { r.queue.request({update(1, 1)}); });
  r.sim.run();
  REQUIRE(r.skips.size() == 1);
  CHECK(r.skips[0] == std::pair<int, int64_t>{2, 1});
  CHECK(r.queue.skipped(2) == 1);
  REQUIRE(r.starts.size() == 3);
  CHECK(r.starts[1].memory == 1);
  CHECK(r.starts[1].at == Time::ms(10));
  CHECK(r.starts[2].memory == 2);
  CHECK(r.starts[2].id == 2);
  CHECK(r.starts[2].at == Time::ms(11));
  // Memory 2 waited from its first request (t=0) to t=11; memory 1 from 6 to 10.
  CHECK(r.queue.queue_ms().stats().max() == Approx(11.0));
  CHECK(r.queue.finished(2) == 1);
  for (const auto& p : r.presents)
    for (const auto& [m, id] : p.batch) CHECK(id != 1);  // the skipped one is never shown
}

TEST_CASE("a memory's images are presented in request order even when a later one finishes first") {
  Recorded r(2);
  // Two renderers: memory 0 asks at t=0 (5 ms) and at t=1 (1 ms). The second
  // finishes at 2 ms but waits for the first, and both are presented at 5 ms.
  r.queue.request({update(0, 5)});
  r.sim.at(Time::ms(1), r.sim.kind("test.tick"), [&r] { r.queue.request({update(0, 1)}); });
  r.sim.run();
  REQUIRE(r.presents.size() == 1);
  CHECK(r.presents[0].at == Time::ms(5));
  REQUIRE(r.presents[0].batch.size() == 2);
  CHECK(r.presents[0].batch[0].second == 0);
  CHECK(r.presents[0].batch[1].second == 1);
}

TEST_CASE("images that name each other are presented together, at the later finish") {
  Recorded r(1);
  // An object moves from memory 3 to memory 0: both redrawn, each named by the other.
  // 0 renders 0-1 ms, 3 renders 1-5 ms: both are shown at 5 ms.
  r.queue.request({update(0, 1, {3}), update(3, 4, {0})});
  r.sim.run();
  REQUIRE(r.presents.size() == 1);
  CHECK(r.presents[0].at == Time::ms(5));
  CHECK(r.presents[0].batch.size() == 2);
}

TEST_CASE("a slow memory a fast image waits for inherits the fast memory's priority") {
  Recorded r(1);
  // t=0: 0 and 3 exchange an object (named by each other); 0 renders 0-6 ms.
  // t=5: memory 0 asks again (6 ms). Without inheritance memory 0 would go
  // first at 6 ms and its images would wait for memory 3 behind it; with it,
  // memory 3 (queued since 0) goes first: 6-8 ms, then memory 0: 8-14 ms.
  r.queue.request({update(0, 6, {3}), update(3, 2, {0})});
  r.sim.at(Time::ms(5), r.sim.kind("test.tick"), [&r] { r.queue.request({update(0, 6)}); });
  r.sim.run();
  REQUIRE(r.starts.size() == 3);
  CHECK(r.starts[1].memory == 3);
  CHECK(r.starts[1].at == Time::ms(6));
  CHECK(r.starts[2].memory == 0);
  CHECK(r.starts[2].at == Time::ms(8));
  REQUIRE(r.presents.size() == 2);
  CHECK(r.presents[0].at == Time::ms(8));
  CHECK(r.presents[1].at == Time::ms(14));
}

TEST_CASE("an image waits for the newer request that replaced the one it named") {
  Recorded r(1);
  // t=0: memory 0 (3 ms) named by nothing; memory 1 (2 ms) waits behind it.
  // Memory 0's second image (t=1, 1 ms) is drawn against memory 1's first request;
  // at t=2 memory 1 asks again, replacing it. 0: 0-3, 1 (second): 3-5, 0 (second): 5-6.
  r.queue.request({update(0, 3), update(1, 2)});
  r.sim.at(Time::ms(1), r.sim.kind("test.tick"), [&r] { r.queue.request({update(0, 1, {1})}); });
  r.sim.at(Time::ms(2), r.sim.kind("test.tick"), [&r] { r.queue.request({update(1, 2)}); });
  r.sim.run();
  REQUIRE(r.presents.size() == 3);
  CHECK(r.presents[1].at == Time::ms(5));
  CHECK(r.presents[1].batch[0].first == 1);
  CHECK(r.presents[2].at == Time::ms(6));
  CHECK(r.presents[2].batch[0].first == 0);
}

TEST_CASE("a request that replaces a waiting one is shown no earlier than the partners the replaced one had") {
  Recorded r(2);
  // Two renderers. t=0: memories 0 (10 ms) and 1 (5 ms) start at once.
  // t=1: memories 2 (10 ms) and 3 (1 ms) exchange an object (each names the other); both wait.
  // t=5: memory 1 is done and shown; memory 2 starts (3 inherits 2's priority; the older id goes first).
  // t=6: memory 3 asks again (1 ms): id 3 is skipped, id 4 takes its place.
  // t=10: memory 0 is done and shown; id 4 starts and is done at 11 ms, but it
  // holds the exchanged object's new state, so it waits for memory 2: both at 15 ms.
  r.queue.request({update(0, 10), update(1, 5)});
  r.sim.at(Time::ms(1), r.sim.kind("test.tick"), [&r] { r.queue.request({update(2, 10, {3}), update(3, 1, {2})}); });
  r.sim.at(Time::ms(6), r.sim.kind("test.tick"), [&r] { r.queue.request({update(3, 1)}); });
  r.sim.run();
  REQUIRE(r.skips.size() == 1);
  CHECK(r.skips[0] == std::pair<int, int64_t>{3, 3});
  REQUIRE(r.presents.size() == 3);
  CHECK(r.presents[0].at == Time::ms(5));
  CHECK(r.presents[1].at == Time::ms(10));
  CHECK(r.presents[2].at == Time::ms(15));
  CHECK(r.presents[2].batch == std::vector<std::pair<int, int64_t>>{{2, 2}, {3, 4}});
}
