// The discrete-event kernel: a clock and a set of pending events, stepping
// from event to event in (time, priority, insertion sequence) order.
//
//   Simulator sim;
//   const KindId tick = sim.kind("display.vsync");
//   sim.at(Time::ms(16), tick, [&] { ... });
//   sim.run();
//
// Callbacks live in a slab of fixed 64-byte slots (inline storage for up to
// 32 bytes of captures, heap beyond that) recycled through a free list, so
// scheduling allocates nothing in the common case; the pending-event set holds
// 16-byte entries only. Cancelling empties the slot; the entry is skipped when
// it reaches the front. A callback runs where it lies in the slab; should the
// slab grow meanwhile, the old slab lives on until the callback returns.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "latsim/des/event_queue.hpp"
#include "latsim/des/inline_function.hpp"
#include "latsim/des/time.hpp"

namespace latsim::des {

/// Among events at the same time, lower priority values run first; default 0.
using Priority = int32_t;
/// An event kind, registered by name with Simulator::kind().
using KindId = uint32_t;

/// Names a scheduled event so it can be cancelled; value 0 is "no event".
struct EventId {
  uint64_t value = 0;
  bool valid() const { return value != 0; }
  friend bool operator==(EventId, EventId) = default;
};

/// Which pending-event set a Simulator uses (results are identical; speed differs).
enum class QueueKind { quaternary_heap, binary_heap };

class Process;
class ProcessPromise;
class DelayAwaitable;

/// Steps simulated time from event to event and runs each event's callback.
class Simulator {
 public:
  /// Events run and (when profiling) wall time spent for one event kind.
  struct KindStats {
    std::string name;
    uint64_t events = 0;
    double wall_s = 0.0;
  };
  /// KindStats summed over the kinds of one model.
  struct ModelStats {
    std::string model;
    uint64_t events = 0;
    double wall_s = 0.0;
  };

  Simulator() : Simulator(QueueKind::quaternary_heap) {}
  explicit Simulator(QueueKind queue_kind);
  ~Simulator();
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  Time now() const { return now_; }
  QueueKind queue_kind() const { return queue_kind_; }

  /// Registers an event kind (or returns the existing id). The text before the
  /// first '.' names the model, e.g. "tracker.sample" belongs to "tracker".
  KindId kind(std::string_view name);
  const std::string& kind_name(KindId id) const;

  /// Schedules fn() at absolute time t; throws std::logic_error if t < now().
  template <class F>
  EventId at(Time t, KindId kind, F&& fn, Priority prio = 0) {
    if (t < now_) [[unlikely]] throw_past(t, kind);
    if (kind >= kinds_.size()) [[unlikely]] throw_unknown_kind(kind);
    const uint32_t s = acquire_slot();
    Slot& slot = slots_[s];
    try {
      slot.fn.construct(std::forward<F>(fn));  // free slots hold no callable
    } catch (...) {
      release_slot(s);
      throw;
    }
    slot.seq = next_seq_++;
    slot.kind = kind;
    ++live_;
    enqueue(QueueEntry{t.ticks(), prio, s});
    return EventId{(static_cast<uint64_t>(slot.generation) << 32) | s};
  }

  /// Schedules fn() at now() + dt; dt must not be negative.
  template <class F>
  EventId after(Time dt, KindId kind, F&& fn, Priority prio = 0) {
    if (dt < Time::zero()) [[unlikely]] throw_negative_delay(dt, kind);
    return at(now_ + dt, kind, std::forward<F>(fn), prio);
  }

  /// Cancels a pending event; returns false if it already ran, was already
  /// cancelled, or never existed. A cancelled event never runs.
  bool cancel(EventId id);

  /// Runs events until none remain or stop() is called.
  void run();
  /// Runs every event with time <= end, then sets now() to end (unless
  /// stop() ended the run earlier). Throws std::logic_error if end < now().
  void run_until(Time end);
  /// Ends the current run() / run_until() after the running event returns.
  void stop() { stop_requested_ = true; }

  /// A flag set from outside the simulation (a signal handler, another
  /// thread): while it is true, runs stop before the next event and
  /// interrupted() says so. nullptr: none.
  void watch_stop_flag(const std::atomic<bool>* flag) { stop_flag_ = flag; }
  /// Whether the last run() / run_until() ended because the stop flag was set.
  bool interrupted() const { return interrupted_; }
  /// Calls `fn` after every `every_events` events (for progress reports;
  /// it must not schedule or cancel). every_events 0: never.
  void watch_progress(uint64_t every_events, std::function<void()> fn);
  /// The kind of the event whose callback threw out of the last run() or
  /// run_until(), if one did.
  std::optional<KindId> failed_kind() const { return failed_kind_; }

  /// Pre-sizes storage for n simultaneously pending events (optional).
  void reserve(std::size_t n);

  bool empty() const { return live_ == 0; }
  std::size_t pending() const { return live_; }
  uint64_t events_executed() const;
  /// Order-sensitive hash over (time ticks, kind-name hash) of every executed
  /// event: equal for identical runs on any platform, different when any
  /// event's time, kind or order changes.
  uint64_t fingerprint() const { return fingerprint_; }

  /// Per kind, in registration order.
  std::vector<KindStats> kind_stats() const;
  /// Per model (kind-name prefix before the first '.'), sorted by name.
  std::vector<ModelStats> model_stats() const;
  /// When on, wall time per event kind is measured with steady_clock.
  void set_profiling(bool on) { profiling_ = on; }
  bool profiling() const { return profiling_; }

  // Coroutine processes (see process.hpp).
  /// Starts p at now() (as an event of kind "process").
  void spawn(Process p);
  /// Starts p at now(); its start and every resumption are events of `kind`.
  void spawn(Process p, KindId kind);
  /// Runs p at once, inside the running event, until it first waits; its
  /// resumptions are events of `kind`. Starting costs no event of its own.
  void start(Process p, KindId kind);
  /// co_await sim.delay(dt): resume dt later (dt >= 0; 0 yields to events already due now).
  DelayAwaitable delay(Time dt);
  /// co_await sim.until(t): resume at absolute time t >= now().
  DelayAwaitable until(Time t);

 private:
  friend class ProcessPromise;

  using Callback = InlineFunction<void(), 32>;

  // A callback with what the loop needs to run and order it; exactly one
  // cache line (aligned so, or a prefetch would fetch only half of it).
  // `fn` is empty while the slot is free or cancelled.
  struct alignas(64) Slot {
    Callback fn;
    uint64_t seq = 0;
    uint32_t generation = 1;
    KindId kind = 0;
  };

  static_assert(sizeof(Callback) + 16 <= 64, "a slot must fit one cache line");

  // What the pending-event set orders: when, at which priority, which slot.
  struct QueueEntry {
    int64_t time_ticks;
    Priority prio;
    uint32_t slot;
  };

  // Orders entries by (time, priority, sequence); the sequence lives in the
  // slot because ties are rare and the entries stay at 16 bytes.
  struct EntryLess {
    const std::unique_ptr<Slot[]>* slots;
    bool operator()(const QueueEntry& a, const QueueEntry& b) const {
      if (a.time_ticks != b.time_ticks) [[likely]] return a.time_ticks < b.time_ticks;
      return tie_less(a, b);
    }
    // Out of line so the common case above compiles to a compare and a flag.
    [[gnu::noinline]] bool tie_less(const QueueEntry& a, const QueueEntry& b) const {
      if (a.prio != b.prio) return a.prio < b.prio;
      return (*slots)[a.slot].seq < (*slots)[b.slot].seq;
    }
  };

  // A registered kind: its name, the name's stable hash and its counters.
  struct KindRecord {
    std::string name;
    uint64_t name_hash = 0;
    uint64_t events = 0;
    double wall_s = 0.0;
  };

  // Free slots form a LIFO list threaded through their `seq` fields (unused
  // while free): the slot freed by the running event is the one the next
  // event's first schedule gets, still in cache.
  static constexpr uint32_t kNoSlot = UINT32_MAX;
  static constexpr std::size_t kMaxSlots = UINT32_MAX;  // indices 0..2^32-2: kNoSlot is none
  uint32_t acquire_slot() {
    if (free_head_ != kNoSlot) [[likely]] {
      const uint32_t s = free_head_;
      free_head_ = static_cast<uint32_t>(slots_[s].seq);
      return s;
    }
    return grow_slots();
  }
  uint32_t grow_slots();
  void reallocate_slots(std::size_t capacity);
  void release_slot(uint32_t s) {
    Slot& slot = slots_[s];
    slot.fn.reset();
    retire_id(slot);
    push_free(s);
  }
  // Makes the slot's current EventId stale (0 would make EventId{0} valid).
  static void retire_id(Slot& slot) {
    if (++slot.generation == 0) slot.generation = 1;
  }
  void push_free(uint32_t s) {
    slots_[s].seq = free_head_;
    free_head_ = s;
  }
  // After the running callback returned or threw: destroys it (in the slab
  // it ran from) and frees its slot.
  void finish_running() {
    const uint32_t s = running_slot_;
    running_slot_ = kNoSlot;
    if (retired_slots_) [[unlikely]] {
      retired_slots_.reset();  // the callback ran there; this slab's copy of the slot is empty
    } else {
      slots_[s].fn.reset();
    }
    push_free(s);
  }

  void enqueue(const QueueEntry& e) {
    if (queue_kind_ == QueueKind::quaternary_heap) {
      if (top_consumed_) {
        quaternary_.replace_top(e);
        top_consumed_ = false;
      } else {
        quaternary_.push(e);
      }
    } else {
      if (top_consumed_) {
        binary_.replace_top(e);
        top_consumed_ = false;
      } else {
        binary_.push(e);
      }
    }
  }

  void run_events(int64_t limit_ticks);
  template <class Q, bool Profile>
  void run_loop(Q& queue, int64_t limit_ticks);

  [[noreturn]] void throw_past(Time t, KindId kind) const;
  [[noreturn]] void throw_unknown_kind(KindId kind) const;
  [[noreturn]] void throw_negative_delay(Time dt, KindId kind) const;

  QueueKind queue_kind_;
  Time now_;
  // The slab: slot_capacity_ slots, of which the first slot_count_ have been
  // handed out at least once.
  std::unique_ptr<Slot[]> slots_;
  std::size_t slot_count_ = 0;
  std::size_t slot_capacity_ = 0;
  uint32_t free_head_ = kNoSlot;
  // The slot whose callback is running, kNoSlot between events; and the slab
  // that callback lies in, if the slab was reallocated while it ran.
  uint32_t running_slot_ = kNoSlot;
  std::unique_ptr<Slot[]> retired_slots_;
  QuaternaryHeap<QueueEntry, EntryLess> quaternary_;
  BinaryHeap<QueueEntry, EntryLess> binary_;
  // True while the running event's entry is still at the front of the queue:
  // the first event it schedules replaces it in one sift (see run_loop).
  bool top_consumed_ = false;
  bool stop_requested_ = false;
  bool running_ = false;
  bool interrupted_ = false;
  const std::atomic<bool>* stop_flag_ = nullptr;
  // Counts down to the next progress call; never reaches 0 without a watcher.
  uint64_t progress_countdown_ = UINT64_MAX;
  uint64_t progress_every_ = 0;
  std::function<void()> progress_fn_;
  std::optional<KindId> failed_kind_;
  bool profiling_ = false;
  uint64_t next_seq_ = 0;
  std::size_t live_ = 0;
  uint64_t fingerprint_ = 0;
  std::vector<KindRecord> kinds_;
  std::map<std::string, KindId, std::less<>> kind_ids_;
  KindId process_kind_ = 0;
  bool process_kind_registered_ = false;
  ProcessPromise* live_processes_ = nullptr;  // intrusive list of unfinished coroutines
};

}  // namespace latsim::des
