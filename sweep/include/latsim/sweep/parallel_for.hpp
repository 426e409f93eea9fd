// Runs independent jobs on a fixed number of worker threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <type_traits>
#include <vector>

namespace latsim::sweep {

/// Calls job(i) (or job(i, worker), the worker from 0 to threads - 1 that
/// runs it, for jobs that keep something per worker) for every i in [0,
/// count) on `threads` workers that take the next index as they become free.
/// Jobs must not throw (catch per job and record the failure by index, so
/// reporting stays in plan order whatever the scheduling).
template <typename Job>
void parallel_for(size_t count, unsigned threads, Job&& job) {
  std::atomic<size_t> next{0};
  auto worker = [&](unsigned w) {
    for (size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) {
      if constexpr (std::is_invocable_v<Job&, size_t, unsigned>) job(i, w);
      else job(i);
    }
  };
  const size_t helpers = std::min<size_t>(threads, count);
  std::vector<std::thread> pool;
  for (size_t t = 1; t < helpers; ++t) pool.emplace_back(worker, static_cast<unsigned>(t));
  worker(0);  // the calling thread is the first worker
  for (auto& thread : pool) thread.join();
}

}  // namespace latsim::sweep
