// What the two halves of Section (params.cpp, params_structure.cpp) share:
// default bounds and range messages; and the check of keys no mode reads.
#pragma once

#include <optional>
#include <string>

#include "latsim/scenario/section.hpp"

namespace latsim::scenario {

// Every span of time a scenario implies (a duration, a period) is at most the
// longest run, 1e6 s, so that any sum of a few of them stays inside int64
// picoseconds (about 9.2e6 s).
constexpr double kLongestSpanSeconds = 1e6;

// The declared range, or the default bounds on the sides it leaves open.
KeySpec bounded_number(const KeySpec& spec);

// What is wrong with x for spec's range, if anything.
std::optional<std::string> range_problem(double x, const KeySpec& spec);

// Checks the value of a key no mode of the scenario reads against the
// declarations `parent_schema` has for `name` (ScenarioDocument::check_unknown_keys).
void check_unread_value(const ObjectSchema& parent_schema, const std::string& name, const nlohmann::json& value,
                        const std::string& parent);

}  // namespace latsim::scenario
