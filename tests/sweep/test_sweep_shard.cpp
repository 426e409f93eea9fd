// Tests for --shard: "I/N" and the array-task variables of Slurm and Grid
// Engine, with expected slices worked out by hand from the schedulers' rules.
#include <catch2/catch.hpp>

#include <map>
#include <string>

#include "latsim/sweep/shard.hpp"

using latsim::sweep::parse_shard;
using latsim::sweep::Shard;

namespace {

latsim::sweep::EnvLookup env_of(std::map<std::string, std::string> vars) {
  return [vars](const std::string& name) -> std::optional<std::string> {
    const auto it = vars.find(name);
    if (it == vars.end()) return std::nullopt;
    return it->second;
  };
}

std::string error_of(const std::string& text, const latsim::sweep::EnvLookup& env = env_of({})) {
  try {
    (void)parse_shard(text, env);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  FAIL("accepted --shard " << text);
  return {};
}

}  // namespace

TEST_CASE("shard option: I/N takes 0-based indices below the count", "[sweep][shard]") {
  const Shard first = parse_shard("0/4", env_of({}));
  CHECK(first.index == 0);
  CHECK(first.count == 4);
  const Shard last = parse_shard("3/4", env_of({}));
  CHECK(last.index == 3);
  // Shard 1 of 3 holds plan positions 1, 4, 7, ...
  const Shard middle = parse_shard("1/3", env_of({}));
  CHECK(middle.contains(1));
  CHECK(middle.contains(4));
  CHECK(middle.contains(7));
  CHECK_FALSE(middle.contains(0));
  CHECK_FALSE(middle.contains(2));
  CHECK(parse_shard("0/1", env_of({})).contains(12345));
}

TEST_CASE("shard option: rejects what is not a slice, saying how to write one", "[sweep][shard]") {
  CHECK_THAT(error_of("4/4"), Catch::Contains("numbered 0 to 3"));
  CHECK_THAT(error_of("1/0"), Catch::Contains("at least 1"));
  CHECK_THAT(error_of("-1/4"), Catch::Contains("non-negative integers"));
  CHECK_THAT(error_of("a/b"), Catch::Contains("non-negative integers"));
  CHECK_THAT(error_of("1/4x"), Catch::Contains("non-negative integers"));
  CHECK_THAT(error_of("2"), Catch::Contains("expected I/N"));
  CHECK_THAT(error_of(""), Catch::Contains("expected I/N"));
}

TEST_CASE("shard option: env reads a Slurm array task", "[sweep][shard]") {
  // sbatch --array=0-7: task 5 is the sixth of eight.
  Shard s = parse_shard("env", env_of({{"SLURM_ARRAY_TASK_ID", "5"}, {"SLURM_ARRAY_TASK_MIN", "0"},
                                       {"SLURM_ARRAY_TASK_MAX", "7"}, {"SLURM_ARRAY_TASK_COUNT", "8"}}));
  CHECK(s.index == 5);
  CHECK(s.count == 8);
  // sbatch --array=1-7:2 runs tasks 1, 3, 5, 7: task 5 is the third, index 2 of 4.
  s = parse_shard("env", env_of({{"SLURM_ARRAY_TASK_ID", "5"}, {"SLURM_ARRAY_TASK_MIN", "1"},
                                 {"SLURM_ARRAY_TASK_MAX", "7"}, {"SLURM_ARRAY_TASK_STEP", "2"},
                                 {"SLURM_ARRAY_TASK_COUNT", "4"}}));
  CHECK(s.index == 2);
  CHECK(s.count == 4);
  // --array=1,3,8: min 1, max 8, three tasks: not one slice per task.
  CHECK_THAT(error_of("env", env_of({{"SLURM_ARRAY_TASK_ID", "3"}, {"SLURM_ARRAY_TASK_MIN", "1"},
                                     {"SLURM_ARRAY_TASK_MAX", "8"}, {"SLURM_ARRAY_TASK_STEP", "1"},
                                     {"SLURM_ARRAY_TASK_COUNT", "3"}})),
             Catch::Contains("not evenly spaced"));
  // Task 4 is not on the grid 1, 3, 5, 7.
  CHECK_THAT(error_of("env", env_of({{"SLURM_ARRAY_TASK_ID", "4"}, {"SLURM_ARRAY_TASK_MIN", "1"},
                                     {"SLURM_ARRAY_TASK_STEP", "2"}, {"SLURM_ARRAY_TASK_COUNT", "4"}})),
             Catch::Contains("not one of 4 evenly spaced indices"));
  CHECK_THAT(error_of("env", env_of({{"SLURM_ARRAY_TASK_ID", "2"}})), Catch::Contains("SLURM_ARRAY_TASK_MIN is not set"));
}

TEST_CASE("shard option: env reads a Grid Engine array task", "[sweep][shard]") {
  // qsub -t 1-10: task 3 is index 2 of 10.
  Shard s = parse_shard("env", env_of({{"SGE_TASK_ID", "3"}, {"SGE_TASK_FIRST", "1"}, {"SGE_TASK_LAST", "10"},
                                       {"SGE_TASK_STEPSIZE", "1"}}));
  CHECK(s.index == 2);
  CHECK(s.count == 10);
  // qsub -t 1-9:3 runs tasks 1, 4, 7: task 7 is index 2 of 3.
  s = parse_shard("env", env_of({{"SGE_TASK_ID", "7"}, {"SGE_TASK_FIRST", "1"}, {"SGE_TASK_LAST", "9"},
                                 {"SGE_TASK_STEPSIZE", "3"}}));
  CHECK(s.index == 2);
  CHECK(s.count == 3);
}

TEST_CASE("shard option: env outside an array job says what to pass instead", "[sweep][shard]") {
  CHECK_THAT(error_of("env"), Catch::Contains("for PBS, LSF or HTCondor pass the index and count as --shard I/N"));
  // Grid Engine marks jobs that are not arrays with "undefined".
  CHECK_THAT(error_of("env", env_of({{"SGE_TASK_ID", "undefined"}})), Catch::Contains("no array task"));
  CHECK_THAT(error_of("env", env_of({{"SLURM_ARRAY_TASK_ID", "x"}})), Catch::Contains("is not a task index"));
}
