// Conformance and randomised stress tests run over every pending-event set.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "latsim/des/event_queue.hpp"

namespace {

// A queue entry shaped like the simulator's, but carrying its own sequence.
struct Entry {
  int64_t time;
  int32_t prio;
  uint64_t seq;
  friend bool operator==(const Entry&, const Entry&) = default;
};

// The simulator's order: time, then priority, then insertion sequence.
struct EntryLess {
  bool operator()(const Entry& a, const Entry& b) const {
    if (a.time != b.time) return a.time < b.time;
    if (a.prio != b.prio) return a.prio < b.prio;
    return a.seq < b.seq;
  }
};

using Binary = latsim::des::BinaryHeap<Entry, EntryLess>;
using Quaternary = latsim::des::QuaternaryHeap<Entry, EntryLess>;
static_assert(latsim::des::EventQueue<Binary, Entry>);
static_assert(latsim::des::EventQueue<Quaternary, Entry>);

// The reference: a vector kept sorted, smallest first.
class SortedVector {
 public:
  void push(const Entry& e) { items_.insert(std::upper_bound(items_.begin(), items_.end(), e, EntryLess{}), e); }
  const Entry& top() const { return items_.front(); }
  const Entry& second() const { return items_[1]; }
  void pop() { items_.erase(items_.begin()); }
  void replace_top(const Entry& e) {
    pop();
    push(e);
  }
  std::size_t size() const { return items_.size(); }
  bool empty() const { return items_.empty(); }

 private:
  std::vector<Entry> items_;
};

}  // namespace

TEMPLATE_TEST_CASE("event queue conformance", "[event_queue]", Binary, Quaternary) {
  TestType q;
  CHECK(q.empty());
  CHECK(q.size() == 0);
  uint64_t seq = 0;
  // Same times with different priorities, and exact ties broken by sequence.
  for (const auto& [t, p] : std::vector<std::pair<int64_t, int32_t>>{
           {5, 0}, {3, 1}, {3, 0}, {3, 0}, {9, -1}, {3, -2}, {5, 0}, {1, 7}}) {
    q.push(Entry{t, p, seq++});
  }
  CHECK(q.size() == 8);
  std::vector<Entry> order;
  while (!q.empty()) {
    order.push_back(q.top());
    q.pop();
  }
  const std::vector<Entry> expected{{1, 7, 7}, {3, -2, 5}, {3, 0, 2}, {3, 0, 3},
                                    {3, 1, 1}, {5, 0, 0},  {5, 0, 6}, {9, -1, 4}};
  CHECK(order == expected);

  q.push(Entry{10, 0, 0});
  q.push(Entry{20, 0, 1});
  q.replace_top(Entry{30, 0, 2});  // removes 10, inserts 30
  CHECK(q.top() == Entry{20, 0, 1});
  q.replace_top(Entry{15, 0, 3});  // a new minimum is fine too
  CHECK(q.top() == Entry{15, 0, 3});
  CHECK(q.size() == 2);
  q.clear();
  CHECK(q.empty());
}

TEMPLATE_TEST_CASE("event queue matches a sorted vector after every operation", "[event_queue][stress]", Binary,
                   Quaternary) {
  std::mt19937_64 rng(12345);
  for (const int64_t time_range : {int64_t{4}, int64_t{1000}, int64_t{1} << 40}) {
    TestType q;
    SortedVector ref;
    uint64_t seq = 0;
    int64_t now = 0;
    for (int step = 0; step < 20000; ++step) {
      const auto op = rng() % 10;
      const Entry e{now + static_cast<int64_t>(rng() % static_cast<uint64_t>(time_range)),
                    static_cast<int32_t>(rng() % 3) - 1, seq++};
      if (op < 4 || ref.empty()) {
        q.push(e);
        ref.push(e);
      } else if (op < 7) {
        now = ref.top().time;
        q.pop();
        ref.pop();
      } else {
        now = ref.top().time;
        q.replace_top(e);
        ref.replace_top(e);
      }
      REQUIRE(q.size() == ref.size());
      REQUIRE(q.empty() == ref.empty());
      if (!ref.empty()) REQUIRE(q.top() == ref.top());
      // What the simulator prefetches: the entry that pop() would bring to
      // the front is always among the hints.
      if (ref.size() >= 2) {
        const auto hints = q.successor_hints();
        REQUIRE(std::find(hints.begin(), hints.end(), ref.second()) != hints.end());
      }
    }
    while (!ref.empty()) {
      REQUIRE(q.top() == ref.top());
      q.pop();
      ref.pop();
    }
    REQUIRE(q.empty());
  }
}
