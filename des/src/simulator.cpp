#include "latsim/des/simulator.hpp"

#include <algorithm>
#include <bit>
#include <chrono>

#include "latsim/des/process.hpp"

namespace latsim::des {

namespace {

// FNV-1a over the bytes of a kind name: stable across platforms and runs,
// unlike std::hash.
uint64_t stable_name_hash(std::string_view name) {
  uint64_t h = 1469598103934665603ull;
  for (const char c : name) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return h;
}

// One step of the fingerprint: rotate-xor-multiply keeps it order-sensitive
// (swapping two events changes the result) at two multiplies per event.
inline uint64_t fingerprint_step(uint64_t h, uint64_t word) {
  return (std::rotl(h, 23) ^ word) * 0x9E3779B97F4A7C15ull;
}

std::string model_of(const std::string& kind_name) { return kind_name.substr(0, kind_name.find('.')); }

// Clears a flag when a run ends, also by exception.
struct RunningGuard {
  bool& flag;
  ~RunningGuard() { flag = false; }
};

}  // namespace

Simulator::Simulator(QueueKind queue_kind)
    : queue_kind_(queue_kind), quaternary_(EntryLess{&slots_}), binary_(EntryLess{&slots_}) {}

Simulator::~Simulator() {
  // Callbacks may hold coroutine handles but never own them: drop them first,
  // then destroy the processes that never finished.
  slots_.reset();
  retired_slots_.reset();
  while (live_processes_ != nullptr) {
    ProcessPromise* p = live_processes_;
    p->detach();
    ProcessPromise::Handle::from_promise(*p).destroy();
  }
}

KindId Simulator::kind(std::string_view name) {
  if (auto it = kind_ids_.find(name); it != kind_ids_.end()) return it->second;
  if (name.empty()) throw std::invalid_argument("event kind names must not be empty (use e.g. \"tracker.sample\")");
  const auto id = static_cast<KindId>(kinds_.size());
  kinds_.push_back(KindRecord{std::string(name), stable_name_hash(name), 0, 0.0});
  kind_ids_.emplace(std::string(name), id);
  return id;
}

const std::string& Simulator::kind_name(KindId id) const {
  if (id >= kinds_.size()) throw_unknown_kind(id);
  return kinds_[id].name;
}

void Simulator::reserve(std::size_t n) {
  if (n > slot_capacity_) reallocate_slots(std::min<std::size_t>(n, kMaxSlots));
  quaternary_.reserve(queue_kind_ == QueueKind::quaternary_heap ? n : 0);
  binary_.reserve(queue_kind_ == QueueKind::binary_heap ? n : 0);
}

uint32_t Simulator::grow_slots() {
  if (slot_count_ == slot_capacity_) {
    if (slot_capacity_ >= kMaxSlots) throw std::length_error("more than 2^32-1 pending events");
    reallocate_slots(std::min<std::size_t>(kMaxSlots, std::max<std::size_t>(64, 2 * slot_capacity_)));
  }
  return static_cast<uint32_t>(slot_count_++);
}

// Moves every callback to a larger slab, except the running one: it stays in
// the old slab, which is kept until the callback returns (finish_running).
void Simulator::reallocate_slots(std::size_t capacity) {
  auto fresh = std::make_unique<Slot[]>(capacity);
  for (std::size_t i = 0; i < slot_count_; ++i) {
    Slot& from = slots_[i];
    Slot& to = fresh[i];
    to.seq = from.seq;
    to.generation = from.generation;
    to.kind = from.kind;
    if (i != running_slot_) to.fn = std::move(from.fn);
  }
  // A second reallocation within the same callback finds the running slot
  // already empty here, and frees this slab at once.
  if (running_slot_ != kNoSlot && slots_[running_slot_].fn) retired_slots_ = std::move(slots_);
  slots_ = std::move(fresh);
  slot_capacity_ = capacity;
}

bool Simulator::cancel(EventId id) {
  const auto s = static_cast<uint32_t>(id.value & 0xffffffffu);
  const auto generation = static_cast<uint32_t>(id.value >> 32);
  if (!id.valid() || s >= slot_count_) return false;
  Slot& slot = slots_[s];
  if (slot.generation != generation || !slot.fn) return false;
  // The entry stays queued; run_loop frees the slot when it reaches the front.
  slot.fn.reset();
  --live_;
  return true;
}

void Simulator::watch_progress(uint64_t every_events, std::function<void()> fn) {
  progress_every_ = fn ? every_events : 0;
  progress_fn_ = std::move(fn);
  progress_countdown_ = progress_every_ == 0 ? UINT64_MAX : progress_every_;
}

void Simulator::run() { run_events(INT64_MAX); }

void Simulator::run_until(Time end) {
  if (end < now_)
    throw std::logic_error("run_until(" + end.str() + ") is before now() = " + now_.str() +
                           "; simulated time cannot go back");
  run_events(end.ticks());
  if (!stop_requested_) now_ = end;
}

void Simulator::run_events(int64_t limit_ticks) {
  if (running_) throw std::logic_error("Simulator::run() called from inside an event; schedule work instead");
  running_ = true;
  RunningGuard guard{running_};
  stop_requested_ = false;
  interrupted_ = false;
  failed_kind_.reset();
  if (queue_kind_ == QueueKind::quaternary_heap) {
    profiling_ ? run_loop<decltype(quaternary_), true>(quaternary_, limit_ticks)
               : run_loop<decltype(quaternary_), false>(quaternary_, limit_ticks);
  } else {
    profiling_ ? run_loop<decltype(binary_), true>(binary_, limit_ticks)
               : run_loop<decltype(binary_), false>(binary_, limit_ticks);
  }
}

// The hot loop. The running event's entry stays at the front of the queue
// while its callback runs (top_consumed_), so that the first event the
// callback schedules replaces it with one sift-down; otherwise it is popped
// afterwards. The callback runs in its slot, unmoved: its id is made stale
// first (an event cannot cancel itself), the slot is freed after it returns,
// and the next event's first schedule reuses it while it is still in cache.
template <class Q, bool Profile>
void Simulator::run_loop(Q& queue, int64_t limit_ticks) {
  while (!stop_requested_ && !queue.empty()) {
    if (stop_flag_ != nullptr && stop_flag_->load(std::memory_order_relaxed)) [[unlikely]] {
      interrupted_ = stop_requested_ = true;
      break;
    }
    if (--progress_countdown_ == 0) [[unlikely]] {
      progress_countdown_ = progress_every_;
      progress_fn_();
    }
    const QueueEntry e = queue.top();
    if (e.time_ticks > limit_ticks) break;
    Slot& slot = slots_[e.slot];
    if (!slot.fn) {  // cancelled
      queue.pop();
      release_slot(e.slot);
      continue;
    }
    const KindId k = slot.kind;
    retire_id(slot);
    running_slot_ = e.slot;
    // The next event's callback is a cache miss away in a large slab: start
    // loading the candidates now, while this event runs. (Hints past the
    // queue's end name slots that exist: the slab never shrinks.)
    for (const QueueEntry& next : queue.successor_hints()) __builtin_prefetch(&slots_[next.slot]);
    now_ = Time::ps(e.time_ticks);
    --live_;
    KindRecord& record = kinds_[k];
    ++record.events;
    fingerprint_ = fingerprint_step(fingerprint_step(fingerprint_, static_cast<uint64_t>(e.time_ticks)),
                                    record.name_hash);
    top_consumed_ = true;
    try {
      if constexpr (Profile) {
        const auto t0 = std::chrono::steady_clock::now();
        slot.fn();
        const auto t1 = std::chrono::steady_clock::now();
        kinds_[k].wall_s += std::chrono::duration<double>(t1 - t0).count();
      } else {
        slot.fn();  // `slot` is not touched again: the slab may have moved
      }
    } catch (...) {
      finish_running();
      failed_kind_ = k;
      if (top_consumed_) {
        queue.pop();
        top_consumed_ = false;
      }
      throw;
    }
    finish_running();
    if (top_consumed_) {
      queue.pop();
      top_consumed_ = false;
    }
  }
}

uint64_t Simulator::events_executed() const {
  // Summed on demand: one counter less to bump in the event loop.
  uint64_t n = 0;
  for (const KindRecord& k : kinds_) n += k.events;
  return n;
}

std::vector<Simulator::KindStats> Simulator::kind_stats() const {
  std::vector<KindStats> out;
  out.reserve(kinds_.size());
  for (const KindRecord& k : kinds_) out.push_back(KindStats{k.name, k.events, k.wall_s});
  return out;
}

std::vector<Simulator::ModelStats> Simulator::model_stats() const {
  std::map<std::string, ModelStats> by_model;
  for (const KindRecord& k : kinds_) {
    const std::string model = model_of(k.name);
    ModelStats& m = by_model[model];
    m.model = model;
    m.events += k.events;
    m.wall_s += k.wall_s;
  }
  std::vector<ModelStats> out;
  out.reserve(by_model.size());
  for (auto& [name, stats] : by_model) out.push_back(std::move(stats));
  return out;
}

void Simulator::throw_past(Time t, KindId kind) const {
  throw std::logic_error("cannot schedule event of kind '" + (kind < kinds_.size() ? kinds_[kind].name : "?") +
                         "' at " + t.str() + ", before now() = " + now_.str() +
                         "; schedule at now() or later");
}

void Simulator::throw_unknown_kind(KindId kind) const {
  throw std::logic_error("unknown event kind id " + std::to_string(kind) +
                         "; obtain ids from Simulator::kind(name) of the same simulator");
}

void Simulator::throw_negative_delay(Time dt, KindId kind) const {
  throw std::logic_error("negative delay " + dt.str() + " for event of kind '" +
                         (kind < kinds_.size() ? kinds_[kind].name : "?") + "'; delays must be >= 0");
}

// ---- processes -------------------------------------------------------------

void Simulator::spawn(Process p) {
  if (!process_kind_registered_) {
    process_kind_ = kind("process");
    process_kind_registered_ = true;
  }
  spawn(std::move(p), process_kind_);
}

void Simulator::spawn(Process p, KindId kind) {
  if (kind >= kinds_.size()) throw_unknown_kind(kind);
  if (!p.handle_) throw std::logic_error("spawn() of an empty Process (already spawned or moved from)");
  ProcessPromise::Handle h = p.release();
  h.promise().attach(*this, kind);
  ProcessPromise::schedule_resume(h, now_);
}

DelayAwaitable Simulator::delay(Time dt) {
  if (dt < Time::zero()) throw std::logic_error("delay(" + dt.str() + ") is negative; delays must be >= 0");
  return DelayAwaitable(now_ + dt);
}

DelayAwaitable Simulator::until(Time t) {
  if (t < now_)
    throw std::logic_error("until(" + t.str() + ") is before now() = " + now_.str() + "; pass a time >= now()");
  return DelayAwaitable(t);
}

void ProcessPromise::attach(Simulator& sim, KindId kind) {
  sim_ = &sim;
  kind_ = kind;
  next_ = sim.live_processes_;
  if (next_ != nullptr) next_->prev_ = this;
  sim.live_processes_ = this;
}

void ProcessPromise::detach() {
  if (prev_ != nullptr) prev_->next_ = next_;
  else if (sim_ != nullptr && sim_->live_processes_ == this) sim_->live_processes_ = next_;
  if (next_ != nullptr) next_->prev_ = prev_;
  prev_ = next_ = nullptr;
}

void Simulator::start(Process p, KindId kind) {
  if (kind >= kinds_.size()) throw_unknown_kind(kind);
  if (!p.handle_) throw std::logic_error("start() of an empty Process (already started or moved from)");
  ProcessPromise::Handle h = p.release();
  h.promise().attach(*this, kind);
  ProcessPromise::resume(h);
}

void ProcessPromise::schedule_resume(Handle h, Time t) {
  Simulator& sim = *h.promise().sim_;
  sim.at(t, h.promise().kind_, [h] { resume(h); });
}

void ProcessPromise::resume(Handle h) {
  h.resume();
  if (!h.done()) return;
  ProcessPromise& p = h.promise();
  std::exception_ptr error = p.error_;
  p.detach();
  h.destroy();
  if (error) std::rethrow_exception(error);
}

}  // namespace latsim::des
