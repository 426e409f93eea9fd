#include "latsim/sweep/keep.hpp"

#include <charconv>
#include <stdexcept>

#include "latsim/scenario/readable.hpp"

namespace latsim::sweep {

namespace {

constexpr std::string_view kExpected =
    "expected figures, first, all or runs=I,J,... (plan positions from 0, as in plan.json)";

size_t parse_index(std::string_view item, std::string_view whole) {
  size_t value = 0;
  const auto [end, error] = std::from_chars(item.data(), item.data() + item.size(), value);
  if (item.empty() || error != std::errc() || end != item.data() + item.size())
    throw std::invalid_argument(scenario::quote_value(whole) + ": " + scenario::quote_value(item) +
                                 " is not a run position; " + std::string(kExpected));
  return value;
}

}  // namespace

KeepPolicy KeepPolicy::parse(std::string_view text) {
  KeepPolicy policy;
  if (text == "figures") return policy;
  if (text == "first" || text == "all") {
    policy.kind = text == "first" ? Kind::first : Kind::all;
    return policy;
  }
  constexpr std::string_view prefix = "runs=";
  if (text.substr(0, prefix.size()) != prefix)
    throw std::invalid_argument(scenario::quote_value(text) + ": " + std::string(kExpected));
  policy.kind = Kind::runs;
  std::string_view list = text.substr(prefix.size());
  while (true) {
    const size_t comma = list.find(',');
    policy.run_indices.insert(parse_index(list.substr(0, comma), text));
    if (comma == std::string_view::npos) break;
    list.remove_prefix(comma + 1);
  }
  return policy;
}

void KeepPolicy::check_runs(size_t run_count) const {
  if (kind != Kind::runs || run_indices.empty() || *run_indices.rbegin() < run_count) return;
  throw std::invalid_argument(scenario::quote_value(text()) + ": run " + std::to_string(*run_indices.rbegin()) +
                              " is not in the plan, whose runs are 0 to " + std::to_string(run_count - 1));
}

bool KeepPolicy::keeps_traces(size_t index, uint64_t replication) const {
  switch (kind) {
    case Kind::figures: return false;
    case Kind::first: return replication == 0;
    case Kind::all: return true;
    case Kind::runs: return run_indices.count(index) > 0;
  }
  return false;
}

std::string KeepPolicy::text() const {
  switch (kind) {
    case Kind::figures: return "figures";
    case Kind::first: return "first";
    case Kind::all: return "all";
    case Kind::runs: break;
  }
  // Appended piece by piece: "," + a temporary trips GCC 12's -Wrestrict false positive.
  std::string out = "runs=";
  for (size_t i : run_indices) {
    if (out.size() > 5) out += ',';
    out += std::to_string(i);
  }
  return out;
}

}  // namespace latsim::sweep
