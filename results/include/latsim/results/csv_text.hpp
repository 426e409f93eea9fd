// One CSV cell as RFC 4180 writes it: every CSV latsim writes (results.csv,
// presentmon.csv, compare.csv, the fidelity table) quotes its text cells here.
#pragma once

#include <string>

namespace latsim::results {

/// `text` as a CSV field: as it is, or quoted (inner quotes doubled) when it
/// holds a comma, a quote or a line break (CR or LF).
std::string csv_field(const std::string& text);

}  // namespace latsim::results
