// The one check every sample a statistic takes passes: a non-finite sample is
// a bug in the model that emitted it, said the same way by every statistic.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>

namespace latsim::stats {

/// Throws std::invalid_argument naming `where` and the sample.
[[noreturn]] inline void throw_non_finite(double x, const char* where) {
  throw std::invalid_argument(std::string(where) + ": sample is " + std::to_string(x) +
                              "; a model emitted a non-finite value, which is a bug in that model");
}

/// Throws as throw_non_finite unless `x` is finite.
inline void require_finite(double x, const char* where) {
  if (!std::isfinite(x)) throw_non_finite(x, where);
}

}  // namespace latsim::stats
