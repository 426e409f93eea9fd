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
// plus clear(), reserve(n) and successor_hints(): a fixed number of entries
// among which is the one that becomes top() next, which lets the simulator
// prefetch the next callback without a branch. The simulator keeps entries
// tiny (time, priority, slot) and the callbacks elsewhere, so each structure
// moves 16-byte records only.
//
// | implementation  | push      | pop       | top  | replace_top | memory       |
// |-----------------|-----------|-----------|------|-------------|--------------|
// | BinaryHeap      | O(log n)  | O(log n)  | O(1) | O(log n)    | n entries    |
// | QuaternaryHeap  | O(log4 n) | O(log n)* | O(1) | O(log n)*   | n entries    |
//
// (*) a 4-ary sift-down does log4(n) levels of 4 comparisons each (as many
// as a binary heap's log2(n) levels of 2), but with the four children in one
// cache line it takes half the cache misses, which is what counts once the
// heap outgrows L1. Pushes sift up over half as many levels.
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <span>
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
  { cq.successor_hints() } -> std::convertible_to<std::span<const Entry, Q::kSuccessorHints>>;
};

/// Allocates with cache-line alignment, so heap families can sit in one line.
template <class T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlign{64};
  CacheLineAllocator() = default;
  template <class U>
  CacheLineAllocator(const CacheLineAllocator<U>&) noexcept {}  // NOLINT(google-explicit-constructor)
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlign)); }
  void deallocate(T* p, std::size_t) noexcept { ::operator delete(p, kAlign); }
  template <class U>
  friend bool operator==(const CacheLineAllocator&, const CacheLineAllocator<U>&) noexcept {
    return true;
  }
};

/// Implicit `Arity`-ary min-heap of trivially copyable entries with a fused
/// replace_top: the event loop pops the next event and usually schedules a
/// new one from its callback, and replace_top does both in a single
/// sift-down instead of a sift-down plus a sift-up. Node i has children
/// Arity*i+1 .. Arity*i+Arity and is stored at index i + Pad of the array.
/// Past the size() live entries the array always holds at least Arity + 1
/// more, initialised (zero or left behind by a pop), so that the root's
/// children can be read as successor hints without a bounds check.
template <class Entry, class Less, std::size_t Arity, std::size_t Pad, class Alloc>
class ImplicitHeap {
  static_assert(Arity == 2 || Arity == 4, "a full family is selected by a tournament of 2 or 4");

 public:
  /// successor_hints() names the root's children.
  static constexpr std::size_t kSuccessorHints = Arity;

  explicit ImplicitHeap(Less less) : less_(std::move(less)) { items_.resize(Pad + kRoom); }

  void push(const Entry& e) {
    if (Pad + size_ + kRoom >= items_.size()) items_.resize(2 * items_.size());
    std::size_t i = size_++;
    Entry* a = data();
    while (i > 0) {
      const std::size_t parent = (i - 1) / Arity;
      if (!less_(e, a[parent])) break;
      a[i] = a[parent];
      i = parent;
    }
    a[i] = e;
  }

  const Entry& top() const { return data()[0]; }

  void pop() {
    const Entry last = data()[size_ - 1];
    --size_;
    if (size_ != 0) sift_down(last);
  }

  void replace_top(const Entry& e) { sift_down(e); }

  /// The root's children, one of which becomes top() after the next pop
  /// (when size() >= 2); past size() they are leftovers, fit only for hints.
  std::span<const Entry, kSuccessorHints> successor_hints() const {
    return std::span<const Entry, kSuccessorHints>(data() + 1, kSuccessorHints);
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  void clear() { size_ = 0; }
  void reserve(std::size_t n) {
    if (Pad + n + kRoom > items_.size()) items_.resize(Pad + n + kRoom);
  }

 private:
  static constexpr std::size_t kRoom = Arity + 1;

  Entry* data() { return items_.data() + Pad; }
  const Entry* data() const { return items_.data() + Pad; }

  // The smallest of a full family a[first .. first+Arity-1]. Index
  // arithmetic instead of ?: keeps the compiler from turning the
  // (unpredictable) outcomes into branches; with four, a small tournament
  // keeps the comparisons independent.
  std::size_t smallest_of_family(const Entry* a, std::size_t first) const {
    const std::size_t l = first + static_cast<std::size_t>(less_(a[first + 1], a[first]));
    if constexpr (Arity == 2) {
      return l;
    } else {
      const std::size_t r = first + 2 + static_cast<std::size_t>(less_(a[first + 3], a[first + 2]));
      const std::size_t take_r = 0 - static_cast<std::size_t>(less_(a[r], a[l]));
      return l ^ ((l ^ r) & take_r);
    }
  }

  // Moves the hole at the root down along the smallest children until `e`
  // fits. (Floyd's bottom-up variant, which skips the comparison with `e`,
  // measured no faster here: a PHOLD event lands mid-heap, not at a leaf.)
  void sift_down(const Entry& e) {
    const std::size_t n = size_;
    Entry* a = data();
    std::size_t i = 0;
    for (;;) {
      const std::size_t first = Arity * i + 1;
      std::size_t best;
      if (first + Arity - 1 < n) {
        best = smallest_of_family(a, first);
      } else if (first < n) {
        best = first;
        for (std::size_t c = first + 1; c < n; ++c)
          if (less_(a[c], a[best])) best = c;
      } else {
        break;
      }
      if (!less_(a[best], e)) break;
      a[i] = a[best];
      i = best;
    }
    a[i] = e;
  }

  Less less_;
  std::vector<Entry, Alloc> items_;
  std::size_t size_ = 0;
};

/// Implicit binary min-heap: the textbook structure, kept as the reference
/// implementation and for comparison.
template <class Entry, class Less>
class BinaryHeap : public ImplicitHeap<Entry, Less, 2, 0, std::allocator<Entry>> {
 public:
  explicit BinaryHeap(Less less = Less{}) : ImplicitHeap<Entry, Less, 2, 0, std::allocator<Entry>>(std::move(less)) {}
};

/// Implicit 4-ary min-heap, the simulator's default. Node i is stored at
/// index i+3 of a cache-line-aligned array: with 16-byte entries the four
/// children of every node then share one 64-byte line, so each level of a
/// sift-down costs at most one cache miss.
template <class Entry, class Less>
class QuaternaryHeap : public ImplicitHeap<Entry, Less, 4, 3, CacheLineAllocator<Entry>> {
 public:
  explicit QuaternaryHeap(Less less = Less{})
      : ImplicitHeap<Entry, Less, 4, 3, CacheLineAllocator<Entry>>(std::move(less)) {}
};

}  // namespace latsim::des
