// Which part of a sweep one task of a batch scheduler's job array runs.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

namespace latsim::sweep {

/// One of `count` disjoint slices of a sweep plan: the runs whose plan
/// position modulo `count` is `index` (0-based).
struct Shard {
  size_t index = 0;
  size_t count = 1;
  std::string source;  ///< where it came from, for messages: "2/8" or "SLURM_ARRAY_TASK_ID=3 ..."

  bool contains(size_t plan_index) const { return plan_index % count == index; }
};

/// Reads one environment variable; empty when unset.
using EnvLookup = std::function<std::optional<std::string>(const std::string& name)>;

/// The process environment (getenv).
std::optional<std::string> process_env(const std::string& name);

/// Parses `--shard` text: "I/N" with 0 <= I < N, or "env" for the array task
/// of the scheduler running us: Slurm (SLURM_ARRAY_TASK_ID, _MIN, _STEP,
/// _COUNT) or Grid Engine (SGE_TASK_ID, SGE_TASK_FIRST, SGE_TASK_LAST,
/// SGE_TASK_STEPSIZE). Throws std::invalid_argument with a one-line reason
/// that says what to do instead.
Shard parse_shard(const std::string& text, const EnvLookup& env = process_env);

}  // namespace latsim::sweep
