// The pending-event set: a small priority-queue interface and its
// implementations, interchangeable under the simulator.
//
// Every implementation offers the same six operations on entries ordered by a
// strict weak order `Less` (the smallest entry is the next event):
//
//   push(e)         insert
//   top()           the smallest entry (queue must not be empty)
//   pop()           remove the smallest entry
//   replace_top(e)  pop() then push(e), fused where the structure allows it
//   size(), empty()
//
// plus clear() and reserve(n). The simulator keeps entries tiny (time,
// priority, slot) and the callbacks elsewhere, so each structure moves 16-byte
// records only.
//
// | implementation  | push      | pop       | top  | replace_top | memory       |
// |-----------------|-----------|-----------|------|-------------|--------------|
// | BinaryHeap      | O(log n)  | O(log n)  | O(1) | O(log n)    | n entries    |
// | QuaternaryHeap  | O(log4 n) | O(log n)* | O(1) | O(log n)*   | n entries    |
//
// (*) a 4-ary sift-down does log4(n) levels of 3 comparisons each; with the
// four children in one cache line that is fewer misses than a binary heap's
// log2(n) levels. Pushes sift up over half as many levels as a binary heap.
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace latsim::des {

/// The operations the simulator needs from a pending-event set.
template <class Q, class Entry>
concept EventQueue = requires(Q q, const Q cq, const Entry& e) {
  q.push(e);
  q.pop();
  q.replace_top(e);
  { cq.top() } -> std::convertible_to<const Entry&>;
  { cq.size() } -> std::convertible_to<std::size_t>;
  { cq.empty() } -> std::convertible_to<bool>;
  q.clear();
};

/// Implicit binary min-heap in a vector: the textbook structure, kept as the
/// reference implementation and for comparison.
template <class Entry, class Less>
class BinaryHeap {
 public:
  explicit BinaryHeap(Less less = Less{}) : less_(std::move(less)) {}

  void push(const Entry& e) {
    std::size_t i = items_.size();
    items_.push_back(e);
    while (i > 0) {
      const std::size_t parent = (i - 1) / 2;
      if (!less_(e, items_[parent])) break;
      items_[i] = items_[parent];
      i = parent;
    }
    items_[i] = e;
  }

  const Entry& top() const { return items_.front(); }

  void pop() {
    const Entry last = items_.back();
    items_.pop_back();
    if (!items_.empty()) sift_down(last);
  }

  void replace_top(const Entry& e) { sift_down(e); }

  std::size_t size() const { return items_.size(); }
  bool empty() const { return items_.empty(); }
  void clear() { items_.clear(); }
  void reserve(std::size_t n) { items_.reserve(n); }

 private:
  // Places `e` at the root's hole and moves it down to where it belongs.
  void sift_down(const Entry& e) {
    const std::size_t n = items_.size();
    std::size_t i = 0;
    for (;;) {
      std::size_t child = 2 * i + 1;
      if (child >= n) break;
      if (child + 1 < n && less_(items_[child + 1], items_[child])) ++child;
      if (!less_(items_[child], e)) break;
      items_[i] = items_[child];
      i = child;
    }
    items_[i] = e;
  }

  Less less_;
  std::vector<Entry> items_;
};

/// Implicit 4-ary min-heap with a fused replace_top, the simulator's default.
///
/// The event loop pops the next event and usually schedules a new one from
/// its callback; replace_top does both in a single sift-down instead of a
/// sift-down plus a sift-up. Node i has children 4i+1..4i+4.
template <class Entry, class Less>
class QuaternaryHeap {
 public:
  explicit QuaternaryHeap(Less less = Less{}) : less_(std::move(less)) {}

  void push(const Entry& e) {
    std::size_t i = items_.size();
    items_.push_back(e);
    while (i > 0) {
      const std::size_t parent = (i - 1) / 4;
      if (!less_(e, items_[parent])) break;
      items_[i] = items_[parent];
      i = parent;
    }
    items_[i] = e;
  }

  const Entry& top() const { return items_.front(); }

  void pop() {
    const Entry last = items_.back();
    items_.pop_back();
    if (!items_.empty()) sift_down(last);
  }

  void replace_top(const Entry& e) { sift_down(e); }

  std::size_t size() const { return items_.size(); }
  bool empty() const { return items_.empty(); }
  void clear() { items_.clear(); }
  void reserve(std::size_t n) { items_.reserve(n); }

 private:
  void sift_down(const Entry& e) {
    const std::size_t n = items_.size();
    Entry* a = items_.data();
    std::size_t i = 0;
    for (;;) {
      const std::size_t first = 4 * i + 1;
      if (first + 3 < n) {
        // Full family: a small tournament keeps the comparisons independent.
        const std::size_t l = less_(a[first + 1], a[first]) ? first + 1 : first;
        const std::size_t r = less_(a[first + 3], a[first + 2]) ? first + 3 : first + 2;
        const std::size_t best = less_(a[r], a[l]) ? r : l;
        if (!less_(a[best], e)) break;
        a[i] = a[best];
        i = best;
        continue;
      }
      if (first >= n) break;
      std::size_t best = first;
      for (std::size_t c = first + 1; c < n; ++c)
        if (less_(a[c], a[best])) best = c;
      if (less_(a[best], e)) {
        a[i] = a[best];
        i = best;
      }
      break;
    }
    a[i] = e;
  }

  Less less_;
  std::vector<Entry> items_;
};

}  // namespace latsim::des
