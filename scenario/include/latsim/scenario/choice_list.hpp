// The choices of a refused value, for an error message of a readable length.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace latsim::scenario {

/// Longest list of choices an error message gives ("expected one of ...").
inline constexpr size_t kChoiceListChars = 200;

/// The choices of a refused value for a message: "a", "b", ... each quoted,
/// cut before the first whole name that would pass `max_chars` and then
/// "… and N more", so that a long list (every figure) is cut at a name,
/// never mid-word, and its message stays within kMessageChars.
std::string choice_list(const std::vector<std::string>& names, size_t max_chars = kChoiceListChars);

}  // namespace latsim::scenario
