// Text from the user shown back to the user: one line, of a readable length.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace latsim::scenario {

/// Longest user value an error message quotes in full.
inline constexpr size_t kQuotedChars = 60;
/// Longest error line latsim prints; anything longer is cut (the start is kept).
inline constexpr size_t kMessageChars = 400;

/// `text` on one line: control characters escaped (\n, \t, \xNN), and when it
/// is longer than `max_chars`, its start followed by "… (N bytes)".
std::string readable(std::string_view text, size_t max_chars = kMessageChars);

/// A user value in double quotes for a message: "abc", or the start of a long
/// one with its size ("aaaa…" (300000 bytes)).
std::string quote_value(std::string_view value);

/// A number for a message as the user gave it: the shortest text that reads
/// back as the same double (17 significant digits at most), so that a value
/// just past a bound never prints as the bound ("1000000000001", not
/// "1e+12"); nan and inf as such.
std::string number_text(double x);

/// An integer for a message, signed or not (a JSON integer past int64's range
/// prints as written, never wrapped).
std::string integer_text(int64_t x);
std::string integer_text(uint64_t x);

/// A JSON pointer for a message: every segment longer than kQuotedChars is cut
/// to its start and its size, so that a key of a megabyte names its place in
/// a line.
std::string readable_pointer(std::string_view pointer);

}  // namespace latsim::scenario
