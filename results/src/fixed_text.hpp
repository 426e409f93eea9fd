// A number as text with a fixed count of decimals, for the warnings the
// figure listeners write.
#pragma once

#include <cstdio>
#include <string>

namespace latsim::results {

/// `v` with `digits` decimals ("%.*f").
inline std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

}  // namespace latsim::results
