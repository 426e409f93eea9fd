#include "latsim/arp/memory_render_queue.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <tuple>

namespace latsim::arp {

MemoryRenderQueue::MemoryRenderQueue(des::Simulator& sim, des::KindId kind, int renderers, int memory_count,
                                     Listener listener)
    : sim_(sim),
      kind_(kind),
      renderers_(renderers),
      idle_(renderers),
      listener_(std::move(listener)),
      memories_(static_cast<size_t>(std::max(memory_count, 0))) {
  if (renderers < 1) throw std::invalid_argument("memory render queue: at least one renderer is needed");
  if (memory_count < 1) throw std::invalid_argument("memory render queue: at least one display memory is needed");
}

std::vector<int64_t> MemoryRenderQueue::request(const std::vector<Update>& updates) {
  const des::Time now = sim_.now();
  std::vector<int64_t> ids;
  std::vector<bool> seen(memories_.size(), false);
  for (const Update& u : updates) {
    if (u.memory < 0 || u.memory >= memory_count() || seen[static_cast<size_t>(u.memory)])
      throw std::invalid_argument("memory render queue: bad or repeated memory " + std::to_string(u.memory));
    if (u.cost < des::Time::zero()) throw std::invalid_argument("memory render queue: negative render cost");
    seen[static_cast<size_t>(u.memory)] = true;
    Memory& m = memories_[static_cast<size_t>(u.memory)];
    Job job;
    job.memory = u.memory;
    job.cost = u.cost;
    job.queued = now;
    // The newer request replaces one that has not started (its position is
    // already stale) and takes its place in the queue.
    // It also inherits what the replaced one had to be shown with: that
    // image's partners may already be drawn and now wait for this one.
    if (m.waiting >= 0) {
      const int64_t old = m.waiting;
      job.queued = jobs_.at(old).queued;
      job.after = std::move(jobs_.at(old).after);
      jobs_.erase(old);
      ++m.skipped;
      if (listener_.skipped) listener_.skipped(u.memory, old);
    }
    const int64_t id = next_id_++;
    m.waiting = id;
    m.newest = id;
    jobs_.emplace(id, std::move(job));
    ids.push_back(id);
  }
  // Named memories resolve to their newest request, this call's included.
  for (size_t i = 0; i < updates.size(); ++i) {
    Job& job = jobs_.at(ids[i]);
    for (int other : updates[i].present_after) {
      if (other < 0 || other >= memory_count())
        throw std::invalid_argument("memory render queue: bad memory " + std::to_string(other));
      const int64_t newest = memories_[static_cast<size_t>(other)].newest;
      if (other != updates[i].memory && newest >= 0) job.after.emplace_back(other, newest);
    }
  }
  dispatch();
  return ids;
}

std::vector<int> MemoryRenderQueue::inherited_priorities() const {
  // A memory runs at the priority of the fastest memory with an image
  // waiting (directly or through others) for one of its newer images.
  std::vector<int> priority(memories_.size());
  for (size_t m = 0; m < priority.size(); ++m) priority[m] = static_cast<int>(m);
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& [id, job] : jobs_) {
      for (const auto& [memory, needed] : job.after) {
        if (memories_[static_cast<size_t>(memory)].presented >= needed) continue;
        int& p = priority[static_cast<size_t>(memory)];
        if (priority[static_cast<size_t>(job.memory)] < p) {
          p = priority[static_cast<size_t>(job.memory)];
          changed = true;
        }
      }
    }
  }
  return priority;
}

void MemoryRenderQueue::dispatch() {
  while (idle_ > 0) {
    // At most one waiting request per memory: a scan is the whole queue.
    const std::vector<int> priority = inherited_priorities();
    int64_t best = -1;
    for (const Memory& m : memories_) {
      if (m.waiting < 0) continue;
      if (best < 0) {
        best = m.waiting;
        continue;
      }
      const Job& a = jobs_.at(m.waiting);
      const Job& b = jobs_.at(best);
      const auto key = [&](const Job& j, int64_t id) {
        return std::tuple(priority[static_cast<size_t>(j.memory)], j.queued, id);
      };
      if (key(a, m.waiting) < key(b, best)) best = m.waiting;
    }
    if (best < 0) return;
    const int64_t id = best;
    Job& job = jobs_.at(id);
    const int memory = job.memory;
    job.state = State::rendering;
    job.started = sim_.now();
    memories_[static_cast<size_t>(memory)].waiting = -1;
    --idle_;
    queue_ms_.add((job.started - job.queued).to_ms());
    if (listener_.started) listener_.started(memory, id);
    sim_.at(job.started + job.cost, kind_, [this, id] { finish(id); });
  }
}

void MemoryRenderQueue::finish(int64_t id) {
  Job& job = jobs_.at(id);
  job.state = State::finished;
  busy_done_ += job.cost;
  ++memories_[static_cast<size_t>(job.memory)].finished;
  ++idle_;
  if (listener_.finished) listener_.finished(job.memory, id);
  present_ready();
  dispatch();
}

bool MemoryRenderQueue::presentable(int64_t id, const std::set<int64_t>& candidates) const {
  const Job& job = jobs_.at(id);
  // Every earlier unresolved request of the memory goes first (or with it).
  for (auto it = jobs_.begin(); it != jobs_.end() && it->first < id; ++it) {
    if (it->second.memory == job.memory && !candidates.contains(it->first)) return false;
  }
  for (const auto& [memory, needed] : job.after) {
    int64_t shown = memories_[static_cast<size_t>(memory)].presented;
    for (int64_t c : candidates) {
      if (jobs_.at(c).memory == memory) shown = std::max(shown, c);
    }
    if (shown < needed) return false;
  }
  return true;
}

void MemoryRenderQueue::present_ready() {
  // The largest set of finished images that can all be shown now: drop those
  // that wait for something outside the set until nothing changes.
  std::set<int64_t> candidates;
  for (const auto& [id, job] : jobs_) {
    if (job.state == State::finished) candidates.insert(id);
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (auto it = candidates.begin(); it != candidates.end();) {
      if (presentable(*it, candidates)) {
        ++it;
        continue;
      }
      it = candidates.erase(it);
      changed = true;
    }
  }
  if (candidates.empty()) return;
  std::vector<std::pair<int, int64_t>> batch;
  for (int64_t id : candidates) {
    const int memory = jobs_.at(id).memory;
    memories_[static_cast<size_t>(memory)].presented = id;
    jobs_.erase(id);
    batch.emplace_back(memory, id);
  }
  if (listener_.presented) listener_.presented(batch);
}

des::Time MemoryRenderQueue::busy_time() const {
  des::Time busy = busy_done_;
  for (const auto& [id, job] : jobs_) {
    if (job.state == State::rendering) busy += sim_.now() - job.started;
  }
  return busy;
}

double MemoryRenderQueue::utilisation(des::Time elapsed) const {
  if (elapsed <= des::Time::zero()) return 0.0;
  return busy_time().to_seconds() / (static_cast<double>(renderers_) * elapsed.to_seconds());
}

}  // namespace latsim::arp
