#include "latsim/sweep/shard.hpp"

#include "latsim/scenario/readable.hpp"

#include <charconv>
#include <cstdint>
#include <cstdlib>

namespace latsim::sweep {

namespace {

// A whole string as a non-negative decimal integer; nothing when it is not one.
std::optional<uint64_t> to_count(const std::string& text) {
  uint64_t value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc{} || ptr != end) return std::nullopt;
  return value;
}

// Values in `why` are quoted as messages quote what a user gave (quote_value: cut, control characters escaped).
[[noreturn]] void reject(const std::string& why) { throw std::invalid_argument("--shard: " + why); }

uint64_t env_integer(const EnvLookup& env, const std::string& name, std::optional<uint64_t> fallback) {
  const auto text = env(name);
  if (!text) {
    if (fallback) return *fallback;
    reject(name + " is not set");
  }
  const auto value = to_count(*text);
  if (!value) reject(name + "=" + scenario::quote_value(*text) + " is not a task index (is this an array job?)");
  return *value;
}

// The slice of an array task with indices first, first + step, ..., of which
// there are `count`: array indices need not start at 0 (Slurm --array=1-8, Grid
// Engine -t 1-8 both number from 1), shards do.
Shard slice_of(uint64_t id, uint64_t first, uint64_t step, uint64_t count, const std::string& source) {
  if (step == 0) reject(source + ": the array's step is 0");
  if (count == 0) reject(source + ": the array has no tasks");
  if (id < first || (id - first) % step != 0 || (id - first) / step >= count)
    reject(source + ": task " + std::to_string(id) + " is not one of " + std::to_string(count) +
           " evenly spaced indices from " + std::to_string(first) + " in steps of " + std::to_string(step) +
           "; submit the array as a range (e.g. 0-" + std::to_string(count - 1) + ") or pass --shard I/N");
  return Shard{static_cast<size_t>((id - first) / step), static_cast<size_t>(count), source};
}

Shard from_slurm(const EnvLookup& env) {
  const uint64_t id = env_integer(env, "SLURM_ARRAY_TASK_ID", std::nullopt);
  const uint64_t first = env_integer(env, "SLURM_ARRAY_TASK_MIN", std::nullopt);
  const uint64_t step = env_integer(env, "SLURM_ARRAY_TASK_STEP", 1);
  const uint64_t count = env_integer(env, "SLURM_ARRAY_TASK_COUNT", std::nullopt);
  const std::string source = "SLURM_ARRAY_TASK_ID=" + std::to_string(id) + " of " + std::to_string(count);
  // An index list such as --array=1,3,8 has a min, a max and a count but no single step.
  if (const auto max = env("SLURM_ARRAY_TASK_MAX")) {
    const auto last = to_count(*max);
    if (!last || *last < first || step == 0 || (*last - first) / step + 1 != count || (*last - first) % step != 0)
      reject(source + ": the array's indices are not evenly spaced (SLURM_ARRAY_TASK_MIN/MAX/STEP/COUNT disagree); "
                      "submit it as a range such as --array=0-" + std::to_string(count == 0 ? 0 : count - 1));
  }
  return slice_of(id, first, step, count, source);
}

Shard from_grid_engine(const EnvLookup& env) {
  const uint64_t id = env_integer(env, "SGE_TASK_ID", std::nullopt);
  const uint64_t first = env_integer(env, "SGE_TASK_FIRST", std::nullopt);
  const uint64_t last = env_integer(env, "SGE_TASK_LAST", std::nullopt);
  const uint64_t step = env_integer(env, "SGE_TASK_STEPSIZE", 1);
  const std::string source = "SGE_TASK_ID=" + std::to_string(id);
  if (last < first || step == 0) reject(source + ": SGE_TASK_FIRST/LAST/STEPSIZE describe no tasks");
  return slice_of(id, first, step, (last - first) / step + 1, source);
}

}  // namespace

std::optional<std::string> process_env(const std::string& name) {
  const char* value = std::getenv(name.c_str());
  if (value == nullptr) return std::nullopt;
  return std::string(value);
}

Shard parse_shard(const std::string& text, const EnvLookup& env) {
  if (text == "env") {
    if (env("SLURM_ARRAY_TASK_ID")) return from_slurm(env);
    // Grid Engine sets SGE_TASK_ID to "undefined" in jobs that are not arrays.
    if (const auto sge = env("SGE_TASK_ID"); sge && *sge != "undefined") return from_grid_engine(env);
    reject("env: no array task in the environment (Slurm SLURM_ARRAY_TASK_ID, Grid Engine SGE_TASK_ID); "
           "for PBS, LSF or HTCondor pass the index and count as --shard I/N");
  }
  const auto slash = text.find('/');
  if (slash == std::string::npos) reject(scenario::quote_value(text) + ": expected I/N (e.g. 0/4) or env");
  const auto index = to_count(text.substr(0, slash));
  const auto count = to_count(text.substr(slash + 1));
  if (!index || !count) reject(scenario::quote_value(text) + ": expected I/N with non-negative integers (e.g. 0/4)");
  if (*count == 0) reject(scenario::quote_value(text) + ": the shard count must be at least 1");
  if (*index >= *count)
    reject(scenario::quote_value(text) + ": the index must be below the count (shards are numbered 0 to " +
           std::to_string(*count - 1) + ")");
  return Shard{static_cast<size_t>(*index), static_cast<size_t>(*count), text};
}

}  // namespace latsim::sweep
