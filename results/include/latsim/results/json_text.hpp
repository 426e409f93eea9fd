// JSON text appended piece by piece, exactly as nlohmann::json::dump(-1)
// writes the same values: for writers that skip building a JSON tree.
#pragma once

#include <cstdint>
#include <string>

namespace latsim::results::json_text {

/// A string as dump writes it: quoted, escaped, text that is not UTF-8 replaced.
void append_string(std::string& out, const std::string& s);
/// The shortest text that reads back as the same double, still a real
/// ("2.0", not "2"); null for infinities and NaN, as dump writes them.
void append_real(std::string& out, double x);
void append_integer(std::string& out, int64_t x);
void append_integer(std::string& out, uint64_t x);

}  // namespace latsim::results::json_text
