// Runs independent jobs on a fixed number of worker threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace latsim::sweep {

/// Calls job(i) for every i in [0, count) on `threads` workers that take the
/// next index as they become free. Jobs must not throw (catch per job and
/// record the failure by index, so reporting stays in plan order whatever the
/// scheduling).
template <typename Job>
void parallel_for(size_t count, unsigned threads, Job&& job) {
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) job(i);
  };
  const size_t helpers = std::min<size_t>(threads, count);
  std::vector<std::thread> pool;
  for (size_t t = 1; t < helpers; ++t) pool.emplace_back(worker);
  worker();  // the calling thread is the first worker
  for (auto& thread : pool) thread.join();
}

}  // namespace latsim::sweep
